//! `reconfig campaign` (issue 32): dispersed cases of one fixture answered in parallel through
//! the one request path. The answers do not depend on the thread count, each row is what
//! `reconfig solve` answers for its case, and a case the checks refuse is a named row.

use reconfig_core::limits::Limits;
use reconfig_host::campaign::dispersion::Dispersion;
use reconfig_host::campaign::table::{same_answers, write_csv};
use reconfig_host::campaign::Campaign;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn fixture_text(stem: &str) -> String {
    std::fs::read_to_string(root().join(format!("fixtures/{stem}.toml"))).expect("test io")
}

fn campaign(stem: &str, dispersions: &[&str], cases: u64) -> Campaign {
    let d = dispersions
        .iter()
        .map(|a| Dispersion::gaussian(a).expect("dispersion"))
        .collect();
    Campaign::new(stem, &fixture_text(stem), d, 7, cases, Limits::default()).expect("campaign")
}

fn csv(c: &Campaign, rows: &[reconfig_host::campaign::Row]) -> Vec<u8> {
    let mut out = Vec::new();
    write_csv(c, rows, false, true, &mut out).expect("csv");
    out
}

#[test]
fn campaign_is_the_same_on_one_thread_and_on_every_core() {
    let c = campaign(
        "wang2018-gco-to-pco-2imp-roe",
        &[
            "relative.initial_roe_m[1]=50",
            "relative.initial_roe_m[2]=20",
        ],
        96,
    );
    let hidden = indicatif::ProgressBar::hidden();
    let one = c.run(1, &hidden).expect("run");
    let four = c.run(4, &hidden).expect("run");
    assert_eq!(one.len(), 96);
    assert!(same_answers(&one, &four));
    // The table without its time column, byte for byte.
    assert_eq!(csv(&c, &one), csv(&c, &four));
    // The cases differ (the dispersions were drawn) and every one planned.
    assert!(one.windows(2).all(|w| w[0].inputs != w[1].inputs));
    assert!(one
        .iter()
        .all(|r| r.usable == Some(true) && r.cost.is_some()));
    // A second campaign of the same seed draws the same cases.
    let again = c.run(2, &hidden).expect("run");
    assert!(same_answers(&one, &again));
}

#[test]
fn the_parts_of_a_campaign_are_its_rows_and_its_table() {
    let c = campaign(
        "huang2012-three-sats-n10",
        &["spacecraft[2].initial[1]=0.2"],
        10,
    );
    let hidden = indicatif::ProgressBar::hidden();
    let whole = c.run(2, &hidden).expect("run");
    let mut table = Vec::new();
    let mut rows = Vec::new();
    for (first, count) in [(0, 3), (3, 0), (3, 4), (7, 3)] {
        let part = c.run_range(first, count, 1, &hidden).expect("part");
        assert_eq!(part.len(), usize::try_from(count).expect("small"));
        write_csv(&c, &part, false, first == 0, &mut table).expect("csv");
        rows.extend(part);
    }
    assert!(same_answers(&whole, &rows));
    assert_eq!(table, csv(&c, &whole));
    // A part past the campaign's cases is refused, named.
    for (first, count) in [(8, 3), (u64::MAX, 2)] {
        let e = c.run_range(first, count, 1, &hidden).expect_err("refused");
        assert!(
            e.to_string().contains(&format!("cases {first} + {count}"))
                && e.to_string().contains("10 cases"),
            "{e}"
        );
    }
}

/// `reconfig solve FILE --json`'s JSON.
fn solve_json(file: &Path) -> serde_json::Value {
    let out = Command::new(env!("CARGO_BIN_EXE_reconfig"))
        .arg("solve")
        .arg(file)
        .arg("--json")
        .output()
        .expect("run reconfig solve");
    serde_json::from_slice(&out.stdout).expect("json")
}

#[test]
fn each_row_is_what_reconfig_solve_answers_for_its_case() {
    let dir = std::env::temp_dir().join(format!("reconfig-campaign-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("test io");
    // Planner B (fixed impulse points) and planner A (three spacecraft, positions dispersed).
    for (stem, dispersion, cost_key) in [
        (
            "wang2018-gco-to-pco-2imp-roe",
            "relative.initial_roe_m[2]=20",
            "total_dv_mps",
        ),
        (
            "huang2012-three-sats-n10",
            "spacecraft[1].initial[0]=0.3",
            "cost",
        ),
    ] {
        let c = campaign(stem, &[dispersion], 6);
        let rows = c.run(2, &indicatif::ProgressBar::hidden()).expect("run");
        for row in rows.iter().step_by(2) {
            let path = dir.join(format!("{stem}-case-{}.toml", row.case));
            std::fs::write(&path, c.case_text(row.case).expect("case")).expect("test io");
            let json = solve_json(&path);
            let cost = json[cost_key].as_f64().expect("cost");
            assert_eq!(
                Some(cost.to_bits()),
                row.cost.map(f64::to_bits),
                "{stem} case {}",
                row.case
            );
            let status = json["status"].as_str().map(str::to_owned);
            assert_eq!(status.as_deref(), Some(row.status.as_str()), "{json}");
            // The JSON a front end is handed (the Python package's) is the one printed,
            // every field but the time.
            let mut buffers = reconfig_host::drivers::answer::buffers();
            let (again, handed) = c.answer_case_json(row.case, &mut buffers);
            let mut handed = handed.expect("a request").expect("json");
            assert!(same_answers(std::slice::from_ref(row), &[again]));
            let mut printed = json.clone();
            for v in [&mut handed, &mut printed] {
                v["solve_time_s"] = serde_json::Value::Null;
            }
            assert_eq!(handed, printed, "{stem} case {}", row.case);
        }
        // The base value moved: the case's file is not the fixture.
        let base = c.case_document(0).expect("case").1[0];
        assert!(base.is_finite() && rows[0].inputs == vec![base]);
    }
}

#[test]
fn a_case_the_checks_refuse_is_a_named_row_and_the_campaign_goes_on() {
    // The chief's eccentricity 0.0678 +- 0.03: some cases put the perigee below 100 km.
    let c = campaign(
        "wang2018-gco-to-pco-2imp",
        &["chief.eccentricity=0.03"],
        200,
    );
    let rows = c.run(2, &indicatif::ProgressBar::hidden()).expect("run");
    let refused: Vec<_> = rows.iter().filter(|r| r.status == "Rejected").collect();
    assert!(
        !refused.is_empty() && refused.len() < 100,
        "{}",
        refused.len()
    );
    for r in &refused {
        assert!(r.message.contains("perigee altitude"), "{}", r.message);
        assert!(r.message.contains("minimum of 100 km"), "{}", r.message);
        assert_eq!((r.usable, r.cost, r.work_units), (None, None, None));
        // Refused exactly when the perigee is below 100 km: a = 7178.137 km.
        let perigee_km = 7178.137 * (1.0 - r.inputs[0]) - 6378.137;
        assert!(perigee_km < 100.0, "{perigee_km}");
    }
    assert!(rows
        .iter()
        .filter(|r| r.status == "Solved")
        .all(|r| 7178.137 * (1.0 - r.inputs[0]) - 6378.137 >= 100.0));
}

#[test]
fn a_case_the_fixtures_own_checks_refuse_keeps_its_numbers_in_its_row() {
    // A LEO arc's client eccentricity 0 +- 0.05: a negative one is refused by the fixture's
    // own check (before any request is made), and its row still says which number it drew.
    let c = campaign("leo-tour-example1-single-arc", &["clients[1][1]=0.05"], 6);
    let mut buffers = reconfig_host::drivers::answer::buffers();
    let rows: Vec<_> = (0..6).map(|k| c.answer_case(k, &mut buffers)).collect();
    let refused: Vec<_> = rows.iter().filter(|r| r.status == "Rejected").collect();
    assert!(!refused.is_empty(), "{rows:?}");
    for r in &refused {
        assert_eq!(r.inputs.len(), 1, "{r:?}");
        assert!(
            r.inputs[0] < 0.0 && r.message.contains("not an elliptic orbit"),
            "{r:?}"
        );
    }
    // The table is square: every row has the case, the number and the answer's columns.
    let table = String::from_utf8(csv(&c, &rows)).expect("utf-8");
    assert_eq!(table.lines().count(), 7, "{table}");
}

#[test]
fn a_dispersion_that_cannot_apply_is_refused_before_any_case_by_name() {
    let text = fixture_text("wang2018-gco-to-pco-2imp");
    let refuse = |arg: &str| {
        let d = vec![Dispersion::gaussian(arg).expect("dispersion")];
        let e = Campaign::new("f", &text, d, 1, 10, Limits::default()).expect_err("refused");
        format!("{e:#}")
    };
    let e = refuse("impulse[0].revolutions=1");
    assert!(
        e.contains("path `impulse[0].revolutions` cannot be dispersed"),
        "{e}"
    );
    assert!(refuse("chief.semi_major=1").contains("no key `semi_major`"));
    // A LEO tour of several arcs is several requests: not a campaign's fixture.
    let leo = fixture_text("leo-tour-example1-printed");
    let e = Campaign::new("leo", &leo, vec![], 1, 10, Limits::default()).expect_err("refused");
    assert!(format!("{e:#}").contains("stands for 4 requests"), "{e:#}");
}

#[test]
fn the_cli_writes_one_row_per_case_and_shows_a_case_as_a_fixture() {
    let run = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_reconfig"))
            .arg("campaign")
            .arg(root().join("fixtures/wang2018-gco-to-pco-2imp-roe.toml"))
            .args(args)
            .output()
            .expect("run reconfig campaign");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).expect("utf-8")
    };
    let disperse = [
        "--disperse",
        "relative.initial_roe_m[1]=50",
        "--cases",
        "40",
    ];
    let table = run(&[
        &disperse[..],
        &["--out", "-", "--no-times", "--threads", "1"],
    ]
    .concat());
    let lines: Vec<&str> = table.lines().collect();
    assert_eq!(lines.len(), 41);
    assert_eq!(
        lines[0],
        "case,relative.initial_roe_m[1],status,usable,cost,work_units,solve_time_s,message"
    );
    let scaled = run(&[&disperse[..], &["--out", "-", "--no-times", "--scaling"]].concat());
    assert_eq!(table, scaled);
    let case = run(&[&disperse[..], &["--show-case", "3"]].concat());
    let drawn: f64 = lines[4]
        .split(',')
        .nth(1)
        .expect("column")
        .parse()
        .expect("f64");
    let doc: toml::Value = toml::from_str(&case).expect("toml");
    assert_eq!(doc["relative"]["initial_roe_m"][1].as_float(), Some(drawn));
}

#[test]
fn the_sweep_answers_are_the_same_on_one_thread_and_on_two() {
    use reconfig_core::pseudospectral::Settings;
    use reconfig_host::drivers::sweep_run::sweep;
    use reconfig_host::families::six;
    // 72 problems: more than one chunk of 64 solved side by side.
    let problems = six::generate_all(12, 9);
    assert_eq!(problems.len(), 72);
    let settings = Settings::default();
    let run = |threads| {
        let mut order = Vec::new();
        let swept = sweep(&problems, None, &settings, None, threads, |i, _, _, _| {
            order.push(i);
            Ok(())
        })
        .expect("sweep");
        (swept, order)
    };
    let ((one, order_one), (two, order_two)) = (run(1), run(2));
    // `each` sees the problems in order, whatever the threads.
    assert_eq!(order_one, (0..72).collect::<Vec<_>>());
    assert_eq!(order_one, order_two);
    let key = |s: &reconfig_host::drivers::sweep_run::Swept| {
        s.outcomes
            .iter()
            .map(|o| (o.family, o.status, o.cost.to_bits()))
            .collect::<Vec<_>>()
    };
    assert_eq!(key(&one), key(&two));
    assert!(one.outcomes.iter().filter(|o| o.status.is_some()).count() > 60);
}
