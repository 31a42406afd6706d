//! The iceoryx2 flight service and feeder, the solver workers and the timing report.
//!
//! Processes talk over three iceoryx2 services under `reconfig/<name>/`:
//! * `rpc`: request-response of byte slices (wire frames, see `reconfig_core::wire`);
//! * `to-service`: event; the feeder (and the service's own workers) wake the dispatcher;
//! * `to-feeder`: event; the dispatcher wakes the feeders after sending a response.
//!
//! Each harness instance has its own iceoryx2 config prefix, so instances (and tests run in
//! parallel) never see each other's shared memory.

pub mod affinity;
pub mod alloc_count;
pub mod check;
pub mod child;
pub mod conduct;
pub mod dispatch;
pub mod faults;
pub mod feeder;
pub mod flood;
pub mod items;
pub mod job;
pub mod leo_onboard;
pub mod order;
pub mod report;
pub mod schedule;
pub mod service;
pub mod worker;

use anyhow::{anyhow, Result};
use iceoryx2::prelude::*;

/// Default iceoryx2 file prefix of a harness instance.
pub const DEFAULT_PREFIX: &str = "reconfig_";
/// Default service name of a harness instance.
pub const DEFAULT_SERVICE: &str = "flight";

/// Most feeders (clients) connected at once.
pub const MAX_CLIENTS: usize = 8;
/// Most requests one feeder keeps in flight.
pub const MAX_IN_FLIGHT: usize = 16;

/// Where a harness instance lives: its iceoryx2 prefix and service name.
#[derive(Clone, Debug, clap::Args)]
pub struct Instance {
    /// iceoryx2 file prefix (keeps harness instances apart; letters, digits, '_' and '-').
    #[arg(long, default_value = DEFAULT_PREFIX)]
    pub prefix: String,
    /// Service name under `reconfig/`.
    #[arg(long, default_value = DEFAULT_SERVICE)]
    pub service: String,
}

impl Default for Instance {
    fn default() -> Self {
        Self {
            prefix: DEFAULT_PREFIX.into(),
            service: DEFAULT_SERVICE.into(),
        }
    }
}

impl Instance {
    /// The iceoryx2 config of this instance (the global defaults with this prefix).
    pub fn config(&self) -> Result<Config> {
        let mut config = Config::default();
        config.global.prefix = FileName::new(self.prefix.as_bytes())
            .map_err(|e| anyhow!("bad iceoryx2 prefix {:?}: {e:?}", self.prefix))?;
        Ok(config)
    }

    /// Full iceoryx2 service name of one of this instance's services.
    pub fn service_name(&self, what: &str) -> Result<ServiceName> {
        let name = format!("reconfig/{}/{what}", self.service);
        ServiceName::new(&name).map_err(|e| anyhow!("bad service name {name:?}: {e:?}"))
    }

    /// A node of this instance.
    pub fn node(&self, name: &str) -> Result<Node<ipc::Service>> {
        let config = self.config()?;
        let node_name =
            NodeName::new(name).map_err(|e| anyhow!("bad node name {name:?}: {e:?}"))?;
        NodeBuilder::new()
            .config(&config)
            .name(&node_name)
            .create::<ipc::Service>()
            .map_err(|e| anyhow!("cannot create iceoryx2 node: {e:?}"))
    }
}

/// A request a feeder sent, waiting for its answer.
pub type Pending = iceoryx2::pending_response::PendingResponse<
    ipc::Service,
    [u8],
    dispatch::RequestHeader,
    [u8],
    dispatch::ServiceOrder,
>;

/// One of an instance's event services (`to-service`, `to-feeder`).
pub type EventService = iceoryx2::service::port_factory::event::PortFactory<ipc::Service>;

impl Instance {
    /// Open the event service `what` of this instance (the flight service creates it).
    pub fn open_event(&self, node: &Node<ipc::Service>, what: &str) -> Result<EventService> {
        node.service_builder(&self.service_name(what)?)
            .event()
            .open()
            .map_err(|e| anyhow!("cannot open event {what}: {e:?}"))
    }
}

/// A notifier on `event`.
pub fn notifier(event: &EventService) -> Result<iceoryx2::port::notifier::Notifier<ipc::Service>> {
    event
        .notifier_builder()
        .create()
        .map_err(|e| anyhow!("cannot create notifier: {e:?}"))
}

/// A listener on `event`.
pub fn listener(event: &EventService) -> Result<iceoryx2::port::listener::Listener<ipc::Service>> {
    event
        .listener_builder()
        .create()
        .map_err(|e| anyhow!("cannot create listener: {e:?}"))
}

/// Remove the instance's persistent global-management segment (iceoryx2 keeps one per
/// prefix). Call it only when no process of this instance runs any more.
pub fn remove_instance_segment(instance: &Instance) -> Result<()> {
    let config = instance.config()?;
    // SAFETY: iceoryx2's precondition is that no process uses this prefix any more; callers
    // use it for their own, unique prefix after their service and feeder have ended.
    unsafe { iceoryx2::testing::remove_global_mgmt_segment::<ipc::Service>(&config) }
        .map_err(|e| anyhow!("cannot remove the global segment: {e:?}"))?;
    Ok(())
}

/// How many of a request-response service's listed servers belong to a node whose process is
/// alive (`Node::list`). `list_servers` lists them: `|f| rpc.dynamic_config().list_servers(f)`.
/// A server of a killed process stays listed until a cleanup removes it; a request sent to it
/// is lost.
pub fn live_servers(
    node: &Node<ipc::Service>,
    list_servers: impl FnOnce(
        &mut dyn FnMut(
            &iceoryx2::service::dynamic_config::request_response::ServerDetails,
        ) -> CallbackProgression,
    ),
) -> usize {
    use iceoryx2::node::NodeView;
    let mut alive = Vec::new();
    let _ = Node::<ipc::Service>::list(node.config(), |state| {
        if let NodeState::Alive(view) = &state {
            alive.push(*view.id());
        }
        CallbackProgression::Continue
    });
    let mut live = 0usize;
    list_servers(&mut |server| {
        if alive.contains(&server.node_id) {
            live += 1;
        }
        CallbackProgression::Continue
    });
    live
}

/// Dead nodes of an instance found by `Node::list`, removed with `try_cleanup_dead_nodes`.
/// Returns how many were dead and how many were cleaned up.
pub fn cleanup_dead_nodes(node: &Node<ipc::Service>) -> (usize, u64) {
    let mut dead = 0usize;
    let _ = Node::<ipc::Service>::list(node.config(), |state| {
        if matches!(state, NodeState::Dead(_)) {
            dead += 1;
        }
        CallbackProgression::Continue
    });
    let state = node.try_cleanup_dead_nodes();
    (dead, state.cleanups)
}

/// Parse a CPU list such as `0,1` or `0-3`.
pub fn parse_cpus(text: &str) -> Result<Vec<usize>> {
    let mut cpus = Vec::new();
    for part in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        if let Some((a, b)) = part.split_once('-') {
            let (a, b): (usize, usize) = (a.trim().parse()?, b.trim().parse()?);
            if b < a {
                anyhow::bail!("bad CPU range {part:?}");
            }
            cpus.extend(a..=b);
        } else {
            cpus.push(part.parse()?);
        }
    }
    if cpus.is_empty() {
        anyhow::bail!("empty CPU list");
    }
    Ok(cpus)
}
