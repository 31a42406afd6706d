//! The planners' host drivers: a fixture's requests answered through the core's one request
//! path (`wire::answer`, [`answer`]) and the answers presented (reports, JSON), and the host's
//! own steps around them (the LEO tour's schedule and truth-model corrections, the planner-A
//! sweep's oracle). The subcommands (`cli/`), the plots, the harness and the firmware build
//! use them; they use no subcommand.
//!
//! * [`answer`]: a request answered and timed, the exit codes, the shared reports of a
//!   refusal, a rejection and an answer without a report of its own;
//! * [`pseudospectral`], [`impulsive`], [`geo_tour`], [`hybrid`]: one planner's report;
//! * [`json`]: the JSON object of an answered fixture of one request, as a value;
//! * [`leo_tour`]: the LEO tour's requests answered in turn (the order, the schedule, the arcs);
//! * [`leo_truth`]: the LEO tour's plans flown in the truth model and re-planned there;
//! * [`leo_report`]: `reconfig solve`'s report of a LEO tour;
//! * [`sweep_oracle`]: the golden answers of the planner-A sweep's oracle;
//! * [`sweep_report`]: the planner-A sweep's table rows and answer lines.

pub mod answer;
pub mod geo_tour;
pub mod hybrid;
pub mod impulsive;
pub mod json;
pub mod leo_report;
pub mod leo_tour;
pub mod leo_truth;
pub mod pseudospectral;
pub mod set_record;
pub mod sweep_oracle;
pub mod sweep_report;
pub mod sweep_run;
