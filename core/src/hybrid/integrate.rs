//! The integrator: Dormand and Prince's 8(5,3) embedded Runge–Kutta pair (Hairer, Nørsett and
//! Wanner, *Solving ODEs I*, the coefficients of their DOP853, as SciPy's `DOP853` also uses
//! them), with the step chosen for a mixed relative/absolute tolerance and bounded by a step
//! count: fixed memory (13 stages of the state on the stack), no heap, and a documented worst
//! case (`max_steps` step trials, accepted, rejected or locating an event, 12 evaluations each;
//! the count runs on over every integration that shares a [`Counts`]).

// The coefficients as published, to 30 digits; the compiler rounds each to the nearest double.
#![allow(clippy::excessive_precision)]

/// Stage times (the system is autonomous: only the tableau's check uses them).
#[cfg(test)]
const C: [f64; 12] = [
    0.0,
    0.052_600_151_958_767_731_878_558_754_448_8,
    0.078_900_227_938_151_597_817_838_131_673_2,
    0.118_350_341_907_227_396_726_757_197_510,
    0.281_649_658_092_772_603_273_242_802_490,
    0.333_333_333_333_333_333_333_333_333_333,
    0.25,
    0.307_692_307_692_307_692_307_692_307_692,
    0.651_282_051_282_051_282_051_282_051_282,
    0.6,
    0.857_142_857_142_857_142_857_142_857_142,
    1.0,
];

/// The stages' coefficients (row s uses the stages before s).
const A: [[f64; 12]; 12] = {
    let mut a = [[0.0; 12]; 12];
    a[1][0] = 5.260_015_195_876_773_187_855_875_444_88e-2;
    a[2][0] = 1.972_505_698_453_789_945_445_953_291_83e-2;
    a[2][1] = 5.917_517_095_361_369_836_337_859_875_49e-2;
    a[3][0] = 2.958_758_547_680_684_918_168_929_937_75e-2;
    a[3][2] = 8.876_275_643_042_054_754_506_789_813_24e-2;
    a[4][0] = 2.413_651_341_592_666_855_023_697_986_65e-1;
    a[4][2] = -8.845_494_793_282_860_853_448_649_627_17e-1;
    a[4][3] = 9.248_340_032_617_920_031_157_379_665_43e-1;
    a[5][0] = 3.703_703_703_703_703_703_703_703_703_7e-2;
    a[5][3] = 1.708_286_087_294_738_712_796_044_821_73e-1;
    a[5][4] = 1.254_676_875_668_224_250_166_918_141_23e-1;
    a[6][0] = 3.710_937_5e-2;
    a[6][3] = 1.702_522_110_195_440_393_149_780_602_72e-1;
    a[6][4] = 6.021_653_898_045_596_068_502_193_972_83e-2;
    a[6][5] = -1.757_812_5e-2;
    a[7][0] = 3.709_200_011_850_479_271_087_793_198_36e-2;
    a[7][3] = 1.703_839_257_122_399_938_102_140_547_05e-1;
    a[7][4] = 1.072_620_304_463_732_846_518_091_991_68e-1;
    a[7][5] = -1.531_943_774_862_440_175_279_361_582_36e-2;
    a[7][6] = 8.273_789_163_814_022_887_584_737_660_02e-3;
    a[8][0] = 6.241_109_587_160_757_171_144_295_778_12e-1;
    a[8][3] = -3.360_892_629_446_941_294_068_571_098_25;
    a[8][4] = -8.682_193_468_417_260_068_181_898_914_53e-1;
    a[8][5] = 2.759_209_969_944_670_830_494_156_007_97e1;
    a[8][6] = 2.015_406_755_047_789_340_861_867_889_79e1;
    a[8][7] = -4.348_988_418_106_995_884_773_662_551_44e1;
    a[9][0] = 4.776_625_364_382_643_658_904_339_085_27e-1;
    a[9][3] = -2.488_114_619_971_667_641_926_425_864_68;
    a[9][4] = -5.902_908_268_368_429_963_714_464_757_43e-1;
    a[9][5] = 2.123_005_144_818_119_423_472_889_498_97e1;
    a[9][6] = 1.527_923_363_288_242_358_325_969_229_38e1;
    a[9][7] = -3.328_821_096_898_486_291_944_532_655_87e1;
    a[9][8] = -2.033_120_170_850_862_613_582_229_285_93e-2;
    a[10][0] = -9.371_424_300_859_873_257_170_402_165_8e-1;
    a[10][3] = 5.186_372_428_844_063_708_300_238_532_09;
    a[10][4] = 1.091_437_348_996_729_578_185_002_546_54;
    a[10][5] = -8.149_787_010_746_926_125_139_972_673_57;
    a[10][6] = -1.852_006_565_999_695_986_415_661_807_01e1;
    a[10][7] = 2.273_948_709_935_050_428_189_700_567_34e1;
    a[10][8] = 2.493_605_552_679_652_389_870_893_967_62;
    a[10][9] = -3.046_764_471_898_219_500_382_366_902_2;
    a[11][0] = 2.273_310_147_516_538_207_923_597_684_49;
    a[11][3] = -1.053_449_546_673_725_019_840_666_898_79e1;
    a[11][4] = -2.000_872_058_224_862_499_096_757_184_44;
    a[11][5] = -1.795_893_186_311_879_891_727_659_505_34e1;
    a[11][6] = 2.794_888_452_941_996_005_084_998_088_37e1;
    a[11][7] = -2.858_998_277_135_023_694_740_655_086_74;
    a[11][8] = -8.872_856_933_530_629_544_335_492_892_58;
    a[11][9] = 1.236_056_717_579_430_306_472_662_015_28e1;
    a[11][10] = 6.433_927_460_157_635_303_559_704_840_46e-1;
    a
};

/// The eighth-order weights.
const B: [f64; 12] = [
    5.429_373_411_656_876_223_805_357_663_63e-2,
    0.0,
    0.0,
    0.0,
    0.0,
    4.450_312_892_752_408_881_441_139_505_66,
    1.891_517_899_314_500_383_042_815_990_44,
    -5.801_203_960_010_584_781_467_211_422_7,
    3.111_643_669_578_198_944_089_160_623_7e-1,
    -1.521_609_496_625_160_785_561_788_068_05e-1,
    2.013_654_008_040_303_483_747_765_375_01e-1,
    4.471_061_572_777_259_051_768_855_690_43e-2,
];

/// The third-order error estimator (13 stages: the last is the derivative at the new point).
const E3: [f64; 13] = [
    B[0] - 0.244_094_488_188_976_377_952_755_905_512,
    0.0,
    0.0,
    0.0,
    0.0,
    B[5],
    B[6],
    B[7],
    B[8] - 0.733_846_688_281_611_857_341_361_741_547,
    B[9],
    B[10],
    B[11] - 0.220_588_235_294_117_647_058_823_529_412e-1,
    0.0,
];

/// The fifth-order error estimator.
const E5: [f64; 13] = [
    0.131_200_449_941_948_807_325_010_299_6e-1,
    0.0,
    0.0,
    0.0,
    0.0,
    -0.122_515_644_637_620_444_072_056_975_3e1,
    -0.495_758_949_657_250_191_521_407_995_2,
    0.166_437_718_245_498_653_696_153_041_5e1,
    -0.350_328_848_749_973_681_688_648_729_0,
    0.334_179_118_713_017_479_029_731_884_1,
    0.819_232_064_851_157_124_657_074_261_3e-1,
    -0.223_553_078_638_862_952_588_442_784_5e-1,
    0.0,
];

/// How close and how long.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Relative tolerance per component.
    pub relative: f64,
    /// Absolute tolerance per component.
    pub absolute: f64,
    /// Most step trials (accepted, rejected and event-locating; [`Counts::step_trials`], over
    /// every integration sharing the `Counts`) before an integration stops unfinished.
    pub max_steps: u32,
}

/// Why an integration stopped before its end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stop {
    /// `max_steps` were taken.
    StepLimit {
        /// The time reached.
        time: f64,
    },
    /// The step fell below the resolution of the time (a singularity: a primary hit).
    StepTooSmall {
        /// The time reached.
        time: f64,
    },
    /// A derivative was not finite.
    NotFinite {
        /// The time reached.
        time: f64,
    },
    /// The bang-bang law switched more often than a propagation allows.
    SwitchLimit {
        /// The time reached.
        time: f64,
    },
}

/// What an integration did.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Counts {
    /// Steps accepted.
    pub accepted: u32,
    /// Steps rejected (and retried smaller).
    pub rejected: u32,
    /// Evaluations of the derivative.
    pub evaluations: u32,
    /// Trial steps that located an event (a switch of the bang-bang law).
    pub event_trials: u32,
}

impl Counts {
    /// Step trials of every kind: accepted, rejected and those that located events. The
    /// integrations' work, which `Tolerance::max_steps` bounds.
    pub fn step_trials(&self) -> u32 {
        self.accepted
            .saturating_add(self.rejected)
            .saturating_add(self.event_trials)
    }
}

/// `y + h Σ_j w_j k_j` over the stages given.
fn combine<const N: usize>(y: &[f64; N], h: f64, weights: &[f64], k: &[[f64; N]]) -> [f64; N] {
    let mut out = *y;
    for (w, kj) in weights.iter().zip(k) {
        if *w != 0.0 {
            for (o, x) in out.iter_mut().zip(kj) {
                *o += h * w * x;
            }
        }
    }
    out
}

/// One DOP853 step of size `h` from `y` (derivative `f0` there): the new point, its derivative,
/// and the error norm relative to the tolerance (accept when ≤ 1).
fn step<const N: usize, F: FnMut(&[f64; N]) -> [f64; N]>(
    f: &mut F,
    y: &[f64; N],
    f0: &[f64; N],
    h: f64,
    tol: &Tolerance,
) -> ([f64; N], [f64; N], f64) {
    let mut k = [[0.0; N]; 13];
    k[0] = *f0;
    k[1] = f(&combine(y, h, &A[1], &k[..1]));
    k[2] = f(&combine(y, h, &A[2], &k[..2]));
    k[3] = f(&combine(y, h, &A[3], &k[..3]));
    k[4] = f(&combine(y, h, &A[4], &k[..4]));
    k[5] = f(&combine(y, h, &A[5], &k[..5]));
    k[6] = f(&combine(y, h, &A[6], &k[..6]));
    k[7] = f(&combine(y, h, &A[7], &k[..7]));
    k[8] = f(&combine(y, h, &A[8], &k[..8]));
    k[9] = f(&combine(y, h, &A[9], &k[..9]));
    k[10] = f(&combine(y, h, &A[10], &k[..10]));
    k[11] = f(&combine(y, h, &A[11], &k[..11]));
    let y_new = combine(y, h, &B, &k[..12]);
    let f_new = f(&y_new);
    k[12] = f_new;
    // SciPy's DOP853 error norm: the fifth-order estimate, tempered by the third-order one.
    let (mut s5, mut s3) = ([0.0; N], [0.0; N]);
    for ((w5, w3), kj) in E5.iter().zip(&E3).zip(&k) {
        for ((a5, a3), x) in s5.iter_mut().zip(s3.iter_mut()).zip(kj) {
            *a5 += w5 * x;
            *a3 += w3 * x;
        }
    }
    let (mut e5, mut e3) = (0.0, 0.0);
    for (((y0, y1), a5), a3) in y.iter().zip(&y_new).zip(&s5).zip(&s3) {
        let scale = tol.absolute + tol.relative * y0.abs().max(y1.abs());
        e5 += (a5 / scale) * (a5 / scale);
        e3 += (a3 / scale) * (a3 / scale);
    }
    let norm = if e5 == 0.0 && e3 == 0.0 {
        0.0
    } else {
        h.abs() * e5 / libm::sqrt((e5 + 0.01 * e3) * N as f64)
    };
    (y_new, f_new, norm)
}

/// Integrate `y' = f(y)` (autonomous) from `y0` over a time `duration` (either sign), steps
/// chosen for `tol`; the end point, or why it stopped. `first_step` starts the step control
/// (any positive size: it adapts).
///
/// # Errors
/// [`Stop`]: the step limit, a step below the time's resolution, or a non-finite derivative.
pub fn integrate<const N: usize, F: FnMut(&[f64; N]) -> [f64; N]>(
    f: F,
    y0: &[f64; N],
    duration: f64,
    first_step: f64,
    tol: &Tolerance,
    counts: &mut Counts,
) -> Result<[f64; N], Stop> {
    integrate_arc(f, |_: &[f64; N]| 1.0, y0, duration, first_step, tol, counts).map(|arc| arc.end)
}

/// Where an arc ended: at its duration, or where its event function turned negative.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc<const N: usize> {
    /// The state there.
    pub end: [f64; N],
    /// The time reached, from the start (signed as the duration).
    pub time: f64,
    /// Whether the event ended it (before the duration).
    pub event: bool,
}

/// Event locations: bisection-secant (Illinois) iterations on the step size at most.
const MAX_EVENT_ITERATIONS: u32 = 60;

/// As [`integrate`], but the arc ends early where `event` (non-negative along the arc; its
/// value at the start is not checked) turns negative: the crossing is located on the last
/// step by the Illinois method on the step size (each trial one DOP853 step from the step's
/// start), to the time's resolution, in at most 60 iterations.
///
/// # Errors
/// As [`integrate`].
pub fn integrate_arc<const N: usize, F, G>(
    mut f: F,
    mut event: G,
    y0: &[f64; N],
    duration: f64,
    first_step: f64,
    tol: &Tolerance,
    counts: &mut Counts,
) -> Result<Arc<N>, Stop>
where
    F: FnMut(&[f64; N]) -> [f64; N],
    G: FnMut(&[f64; N]) -> f64,
{
    let direction = if duration < 0.0 { -1.0 } else { 1.0 };
    let end = duration.abs();
    let mut t = 0.0;
    let mut y = *y0;
    let mut fy = f(&y);
    counts.evaluations = counts.evaluations.saturating_add(1);
    let mut h = first_step.abs().min(end);
    while t < end {
        if counts.step_trials() >= tol.max_steps {
            return Err(Stop::StepLimit {
                time: t * direction,
            });
        }
        let last = t + h >= end;
        let size = if last { end - t } else { h };
        if size <= f64::EPSILON * end.max(1.0) {
            if last {
                break;
            }
            return Err(Stop::StepTooSmall {
                time: t * direction,
            });
        }
        let (y_new, f_new, err) = step(&mut f, &y, &fy, size * direction, tol);
        counts.evaluations = counts.evaluations.saturating_add(12);
        if !err.is_finite() || f_new.iter().any(|x| !x.is_finite()) {
            if size <= f64::EPSILON * end.max(1.0) * 16.0 {
                return Err(Stop::NotFinite {
                    time: t * direction,
                });
            }
            counts.rejected = counts.rejected.saturating_add(1);
            h = size * 0.2;
            continue;
        }
        // Grow or shrink by the error's eighth root, within [0.2, 10], with a safety factor.
        let factor = if err == 0.0 {
            10.0
        } else {
            (0.9 * libm::pow(err, -1.0 / 8.0)).clamp(0.2, 10.0)
        };
        if err > 1.0 {
            counts.rejected = counts.rejected.saturating_add(1);
            h = size * factor.min(1.0);
            continue;
        }
        counts.accepted = counts.accepted.saturating_add(1);
        let g_new = event(&y_new);
        if g_new < 0.0 {
            // The crossing lies in (0, size]: Illinois on the step size, g at 0 taken as
            // non-negative (a switch just left lies on the arc's side by construction).
            let (mut lo, mut hi) = (0.0, size);
            let (mut g_lo, mut g_hi) = (event(&y).max(0.0), g_new);
            let mut at = (y_new, hi);
            let mut side = 0_i8;
            for _ in 0..MAX_EVENT_ITERATIONS {
                if hi - lo <= f64::EPSILON * (t + hi).max(1.0) {
                    break;
                }
                let mid = if g_lo - g_hi > 0.0 {
                    (lo * (-g_hi) + hi * g_lo) / (g_lo - g_hi)
                } else {
                    0.5 * (lo + hi)
                };
                let mid = if mid > lo && mid < hi {
                    mid
                } else {
                    0.5 * (lo + hi)
                };
                if counts.step_trials() >= tol.max_steps {
                    return Err(Stop::StepLimit {
                        time: (t + lo) * direction,
                    });
                }
                let (y_mid, _, _) = step(&mut f, &y, &fy, mid * direction, tol);
                counts.evaluations = counts.evaluations.saturating_add(12);
                counts.event_trials = counts.event_trials.saturating_add(1);
                let g_mid = event(&y_mid);
                if g_mid < 0.0 {
                    hi = mid;
                    g_hi = g_mid;
                    at = (y_mid, mid);
                    if side == -1 {
                        g_lo *= 0.5;
                    }
                    side = -1;
                } else {
                    lo = mid;
                    g_lo = g_mid;
                    if side == 1 {
                        g_hi *= 0.5;
                    }
                    side = 1;
                }
            }
            // The first point past the crossing: the arc's event is there.
            return Ok(Arc {
                end: at.0,
                time: (t + at.1) * direction,
                event: true,
            });
        }
        t = if last { end } else { t + size };
        y = y_new;
        fy = f_new;
        h = size * factor;
    }
    Ok(Arc {
        end: y,
        time: t * direction,
        event: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The weights of an explicit Runge–Kutta method sum to one, each row of A to its stage time.
    #[test]
    fn the_tableau_is_consistent() {
        assert!((B.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        for (row, c) in A.iter().zip(C) {
            assert!((row.iter().sum::<f64>() - c).abs() < 1e-14, "{c}");
        }
        // The estimators weigh differences of solutions: they sum to zero.
        assert!(E5.iter().sum::<f64>().abs() < 1e-14);
        assert!(E3.iter().sum::<f64>().abs() < 1e-14);
    }

    /// The harmonic oscillator around a full turn and back, to the tolerance asked.
    #[test]
    fn an_oscillator_comes_back_to_its_start() {
        let tol = Tolerance {
            relative: 1e-12,
            absolute: 1e-14,
            max_steps: 10_000,
        };
        let mut counts = Counts::default();
        let turn = 2.0 * core::f64::consts::PI;
        let y = integrate(
            |y: &[f64; 2]| [y[1], -y[0]],
            &[1.0, 0.0],
            10.0 * turn,
            0.1,
            &tol,
            &mut counts,
        )
        .unwrap();
        assert!((y[0] - 1.0).abs() < 1e-10 && y[1].abs() < 1e-10, "{y:?}");
        assert!(counts.accepted > 10 && counts.accepted < 2000, "{counts:?}");
        let back = integrate(
            |y: &[f64; 2]| [y[1], -y[0]],
            &y,
            -2.5,
            0.1,
            &tol,
            &mut counts,
        )
        .unwrap();
        assert!((back[0] - libm::cos(2.5)).abs() < 1e-10, "{back:?}");
        // A step limit stops it, saying where.
        let mut few = Counts::default();
        let short = Tolerance {
            max_steps: 3,
            ..tol
        };
        let stop = integrate(
            |y: &[f64; 2]| [y[1], -y[0]],
            &[1.0, 0.0],
            turn,
            0.1,
            &short,
            &mut few,
        );
        assert!(matches!(stop, Err(Stop::StepLimit { time }) if time > 0.0 && time < turn));
        assert_eq!(few.accepted + few.rejected, 3);
    }
}
