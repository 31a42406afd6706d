//! The order of service, read from one client's answers.
//!
//! Every answer carries its request's turn and the number of turns the service had given when
//! it received the request ([`ServiceOrder`]). For each of a client's requests, the turns given
//! between its receipt and its own turn went either to the client's own earlier requests or to
//! other clients. The round-robin promises that while a client has a request queued, each other
//! client gets at most one turn per turn of its own, plus one: `others <= (own + 1) x (other
//! clients)`. That is an order, not a speed: it holds on any machine, however loaded.

use super::dispatch::{ServiceOrder, NO_TURN};

/// What one request waited for, in turns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Waited {
    /// Turns of the client's own earlier requests between this one's receipt and its turn.
    pub own: u64,
    /// Turns of other clients in that span.
    pub others: u64,
}

/// The wait of each answer given in a turn, in the order given (answers outside the turns,
/// `Expired`, are left out). `served` holds every answer of one client.
pub fn waits(served: &[ServiceOrder]) -> Vec<Waited> {
    let mut own: Vec<u64> = served
        .iter()
        .map(|o| o.turn)
        .filter(|t| *t != NO_TURN)
        .collect();
    own.sort_unstable();
    served
        .iter()
        .filter(|o| o.turn != NO_TURN && o.turn >= o.received_at_turn)
        .map(|o| {
            let span = o.turn - o.received_at_turn;
            // Own turns t with received_at_turn <= t < turn.
            let from = own.partition_point(|t| *t < o.received_at_turn);
            let to = own.partition_point(|t| *t < o.turn);
            let own_between = (to - from) as u64;
            Waited {
                own: own_between,
                others: span - own_between.min(span),
            }
        })
        .collect()
}

/// Requests that waited for more turns of others than the round-robin allows with
/// `other_clients` other clients.
pub fn out_of_turn(waits: &[Waited], other_clients: u64) -> usize {
    waits
        .iter()
        .filter(|w| w.others > (w.own + 1) * other_clients)
        .count()
}

/// Turns given to other clients between this client's first receipt and its last turn.
pub fn other_turns(served: &[ServiceOrder]) -> u64 {
    let turns: Vec<&ServiceOrder> = served.iter().filter(|o| o.turn != NO_TURN).collect();
    let (Some(first), Some(last)) = (
        turns.iter().map(|o| o.received_at_turn).min(),
        turns.iter().map(|o| o.turn).max(),
    ) else {
        return 0;
    };
    (last + 1).saturating_sub(first) - turns.len() as u64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn o(received_at_turn: u64, turn: u64) -> ServiceOrder {
        ServiceOrder {
            turn,
            received_at_turn,
        }
    }

    #[test]
    fn own_and_other_turns_are_told_apart() {
        // Requests received at turn 0 and 0, served at turns 1 and 3: the first waited for one
        // other turn (0), the second for its own (1) and two others (0, 2).
        let w = waits(&[o(0, 1), o(0, 3)]);
        assert_eq!(
            w,
            [Waited { own: 0, others: 1 }, Waited { own: 1, others: 2 }]
        );
        assert_eq!(out_of_turn(&w, 1), 0);
        assert_eq!(other_turns(&[o(0, 1), o(0, 3)]), 2);
        // Three turns of another client before its first request: out of turn.
        let w = waits(&[o(5, 8)]);
        assert_eq!(w, [Waited { own: 0, others: 3 }]);
        assert_eq!(out_of_turn(&w, 1), 1);
        assert_eq!(out_of_turn(&w, 3), 0);
    }

    #[test]
    fn expired_answers_are_left_out() {
        let w = waits(&[o(0, NO_TURN), o(0, 0)]);
        assert_eq!(w, [Waited { own: 0, others: 0 }]);
        assert_eq!(other_turns(&[o(0, NO_TURN)]), 0);
    }
}
