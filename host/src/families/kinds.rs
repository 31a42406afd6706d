//! The kinds of the tuning and held-out sets: their names (kebab-case, the table's order),
//! which are tight, and one problem of a kind from a seeded stream.

use super::bound::{ends_apart, finish, Common};
use super::{motion, overtaking, placements, swaps};
use rand_chacha::ChaCha8Rng;
use reconfig_core::pseudospectral::{Problem, Spacecraft};

/// One kind of generated problem.
#[derive(Clone, Copy)]
pub struct Kind {
    /// Its name (kebab-case), the `family` of its JSON lines and its table row.
    pub name: &'static str,
    /// Tight: the control bound 1.15-1.5 times the need (`bound::TIGHT_FACTOR`).
    pub tight: bool,
    /// Its spacecraft, after the common draws (which it may change).
    make: fn(&mut ChaCha8Rng, &mut Common) -> Vec<Spacecraft>,
}

impl std::fmt::Debug for Kind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Kind")
            .field("name", &self.name)
            .field("tight", &self.tight)
            .finish()
    }
}

const fn kind(
    name: &'static str,
    make: fn(&mut ChaCha8Rng, &mut Common) -> Vec<Spacecraft>,
) -> Kind {
    Kind {
        name,
        tight: false,
        make,
    }
}

const fn tight(
    name: &'static str,
    make: fn(&mut ChaCha8Rng, &mut Common) -> Vec<Spacecraft>,
) -> Kind {
    Kind {
        name,
        tight: true,
        make,
    }
}

/// Every kind, in table order; problem `i` of a set is of kind `KINDS[i % KINDS.len()]`.
pub const KINDS: [Kind; 22] = [
    kind("random-placements", placements::random_placements),
    kind("antipodal-circle", swaps::antipodal_circle),
    kind("antipodal-tilted-circle", swaps::antipodal_tilted_circle),
    kind("antipodal-sphere", swaps::antipodal_sphere),
    kind("antipodal-cube", swaps::antipodal_cube),
    kind("antipodal-tetrahedron", swaps::antipodal_tetrahedron),
    kind("cube-mirror", swaps::cube_mirror),
    kind("cube-rotation", swaps::cube_rotation),
    kind("cube-permutation", swaps::cube_permutation),
    kind("ring-rotation", motion::ring_rotation),
    kind("ring-rotation-climb", motion::ring_rotation_climb),
    kind("collinear-reversal", motion::collinear_reversal),
    tight("head-on-tight", motion::head_on_tight),
    tight("random-tight", placements::random_tight),
    kind("fly-through-stream", motion::fly_through_stream),
    kind("convergence", motion::convergence),
    kind("overtaking", overtaking::overtaking),
    kind("repack-ball", placements::repack_ball),
    kind("repack-grid", placements::repack_grid),
    kind("repack-hexagonal", placements::repack_hexagonal),
    kind("repack-cubic", placements::repack_cubic),
    kind("mixed-masses", placements::mixed_masses),
];

/// The kinds' names, in table order.
pub fn names() -> Vec<&'static str> {
    KINDS.iter().map(|k| k.name).collect()
}

/// The kind called `name`.
pub fn by_name(name: &str) -> Option<&'static Kind> {
    KINDS.iter().find(|k| k.name == name)
}

/// Draws of a kind before one is kept (each kind builds its ends apart; this only guards).
const MAX_DRAWS: usize = 64;

/// One problem of `kind`: the common draws, the kind's spacecraft, the control bound. A draw
/// whose ends are closer than `bound::END_CLEARANCE_LU` is drawn again (from the same stream).
pub fn generate(kind: &Kind, rng: &mut ChaCha8Rng) -> Problem {
    let mut draw = || {
        let mut common = Common::draw(rng, kind.tight);
        let crafts = (kind.make)(rng, &mut common);
        finish(&common, crafts)
    };
    let mut p = draw();
    for _ in 1..MAX_DRAWS {
        if ends_apart(&p) {
            break;
        }
        p = draw();
    }
    p
}
