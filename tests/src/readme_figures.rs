//! The README's Cortex-M7 lines of "Where we stand", generated from the two M7 records
//! (`fixtures/golden/m7-figures.toml`, `fixtures/golden/m7-figures-leo.toml`, which the QEMU
//! tests write) between `<!-- readme-m7:begin ... -->` and `<!-- readme-m7:end -->`: one short
//! line per figure (what, target, measured, met or not, where it is explained).
//! `tests/tests/m7_docs.rs` fails when the README differs from what the records generate.

use crate::m7_record::{grouped, int, root, splice_between, RECORD_FILE};
use std::fmt::Write as _;

/// The README, relative to the workspace.
pub const README_FILE: &str = "README.md";
/// The LEO image's record, relative to the workspace.
pub const LEO_RECORD_FILE: &str = "fixtures/golden/m7-figures-leo.toml";
/// Start marker of the generated lines.
pub const README_BEGIN: &str =
    "<!-- readme-m7:begin (generated from fixtures/golden/m7-figures*.toml; do not edit) -->";
/// End marker of the generated lines.
pub const README_END: &str = "<!-- readme-m7:end -->";

/// A fixture's or an image's figures: a table of the record.
type Entry = toml::Table;

fn parse(text: &str, file: &str) -> Result<toml::Table, String> {
    toml::from_str(text).map_err(|e| format!("{file}: {e}"))
}

fn entries<'a>(record: &'a toml::Table, key: &str) -> Vec<&'a Entry> {
    record
        .get(key)
        .and_then(toml::Value::as_array)
        .map(|a| a.iter().filter_map(toml::Value::as_table).collect())
        .unwrap_or_default()
}

fn named<'a>(list: &[&'a Entry], name: &str) -> Result<&'a Entry, String> {
    list.iter()
        .copied()
        .find(|e| e.get("name").and_then(toml::Value::as_str) == Some(name))
        .ok_or_else(|| format!("no record entry named {name}"))
}

/// Instructions in millions, one decimal (`6.7 M`).
fn mega(v: u64) -> String {
    format!("{:.1} M", v as f64 / 1e6)
}

/// Instructions in billions, two decimals (`0.46 G`).
fn giga(v: u64) -> String {
    format!("{:.2} G", v as f64 / 1e9)
}

fn met(ok: bool) -> &'static str {
    if ok {
        "met"
    } else {
        "**not met**"
    }
}

/// One line: what, target, measured, met, link.
fn line(md: &mut String, what: &str, target: &str, measured: &str, ok: bool, link: &str) {
    let _ = writeln!(
        md,
        "| {what} | {target} | {measured} | {} | {link} |",
        met(ok)
    );
}

/// The largest instruction count over `fixtures` whose name satisfies `pick`, with its name.
fn largest(fixtures: &[&Entry], pick: impl Fn(&str) -> bool) -> Result<(u64, String), String> {
    let mut best: Option<(u64, String)> = None;
    for f in fixtures {
        let name = f.get("name").and_then(toml::Value::as_str).unwrap_or("");
        if pick(name) {
            let n = int(f, "instructions")?;
            if best.as_ref().is_none_or(|(b, _)| n > *b) {
                best = Some((n, name.to_owned()));
            }
        }
    }
    best.ok_or_else(|| "no fixture matched".to_owned())
}

/// The generated lines (without the markers) for the two records' texts.
///
/// # Errors
/// A record does not parse or lacks a figure.
pub fn render_readme(record: &str, leo_record: &str) -> Result<String, String> {
    let record = parse(record, RECORD_FILE)?;
    let leo = parse(leo_record, LEO_RECORD_FILE)?;
    let fixtures = entries(&record, "fixture");
    let geo = entries(&record, "geo_fixture");
    let leo_fixtures = entries(&leo, "leo_fixture");
    let firmware = "[firmware](docs/firmware.md)";
    let mut md = String::new();

    let paper = int(
        named(&fixtures, "huang2012-three-sats-n10")?,
        "instructions",
    )?;
    line(
        &mut md,
        "M7: planner A, paper case N = 10",
        "≤ 40 M instructions",
        &mega(paper),
        paper <= 40_000_000,
        firmware,
    );
    let crossing = int(named(&fixtures, "crossing-8-sats-n16")?, "instructions")?;
    line(
        &mut md,
        "M7: planner A, 8-spacecraft crossing",
        "≤ 200 M instructions",
        &mega(crossing),
        crossing <= 200_000_000,
        firmware,
    );
    // Requests given as osculating states convert them first (their budget is 20 M).
    let (fixed, fixed_name) = largest(&fixtures, |n| {
        n.ends_with("+fixed-point") && !n.contains("-state")
    })?;
    line(
        &mut md,
        "M7: planner B, fixed-point plan, every mean-element or ROE fixture",
        "≤ 2 M instructions",
        &format!("{} at most (`{fixed_name}`)", mega(fixed)),
        fixed <= 2_000_000,
        firmware,
    );
    let searches: Vec<u64> = (2..=4)
        .map(|k| {
            int(
                named(&fixtures, &format!("wang2018-gco-to-pco-search-{k}imp"))?,
                "instructions",
            )
        })
        .collect::<Result<_, _>>()?;
    line(
        &mut md,
        "M7: planner B, search for 2 / 3 / 4 impulses",
        "≤ 400 M instructions",
        &searches
            .iter()
            .map(|&n| mega(n))
            .collect::<Vec<_>>()
            .join(" / "),
        searches.iter().all(|&n| n <= 400_000_000),
        firmware,
    );
    let mut images: Vec<(String, u64, u64)> = entries(&record, "image")
        .iter()
        .map(|i| {
            let planner = i
                .get("planner")
                .and_then(toml::Value::as_str)
                .unwrap_or("?");
            Ok((
                planner.to_owned(),
                int(i, "ram_bytes")?,
                int(i, "ram_bytes_budget")?,
            ))
        })
        .collect::<Result<_, String>>()?;
    if let Some(g) = record.get("geo_image").and_then(toml::Value::as_table) {
        images.push((
            "geo-tour".into(),
            int(g, "ram_bytes")?,
            int(g, "ram_bytes_budget")?,
        ));
    }
    let worst = images
        .iter()
        .max_by_key(|(_, ram, budget)| ram * 1000 / budget.max(&1))
        .ok_or("no images in the record")?;
    line(
        &mut md,
        "M7: RAM (static + stack) of each one-planner image",
        &format!("≤ {} B", grouped(worst.2)),
        &format!(
            "{} B at most ({}: {} B to spare)",
            grouped(worst.1),
            worst.0,
            grouped(worst.2.saturating_sub(worst.1))
        ),
        images.iter().all(|(_, ram, budget)| ram <= budget),
        firmware,
    );
    let published = int(named(&geo, "geo-servicing-published-60d")?, "instructions")?;
    let sixteen = int(named(&geo, "geo-servicing-16-targets")?, "instructions")?;
    line(
        &mut md,
        "M7: GEO tour, published 60-day case / 16 clients",
        "≤ 20 M instructions",
        &format!("{} / {}", mega(published), mega(sixteen)),
        published.max(sixteen) <= 20_000_000,
        "[geo-tour](docs/geo-tour.md)",
    );
    // Planners A and B: the default budget times the largest instructions per unit over their
    // charged kernel cases (each case measured alone on its dearest path; planner B's with
    // every Kepler solve at its Newton-step limit).
    // The LEO arc's and sequencing's likewise (one unit, one default budget).
    for (planner, docs, link) in [
        ("planner A", &crate::m7_record::KERNELS_A_DOCS, firmware),
        ("planner B", &crate::m7_record::KERNELS_B_DOCS, firmware),
        (
            "LEO tour arc or sequencing",
            &crate::m7_record::KERNELS_LEO_DOCS,
            "[leo-tour](docs/leo-tour.md)",
        ),
    ] {
        let ratio =
            crate::m7_record::kernels_worst_ratio(&record, docs.key)?.map_or(0.0, |(r, _)| r);
        let bound = (ratio * docs.budget as f64).ceil() as u64;
        line(
            &mut md,
            &format!(
                "M7: {planner}, any request within the limits (budget × kernels' largest \
                 instructions per unit)"
            ),
            "≤ 400 M instructions",
            &format!(
                "≤ {} by the kernels measured in CI ({ratio:.2} per unit × {:.1} M units)",
                if bound >= 1_000_000_000 {
                    giga(bound)
                } else {
                    mega(bound)
                },
                docs.budget as f64 / 1e6
            ),
            ratio > 0.0 && bound <= 400_000_000,
            link,
        );
    }
    let budget = record
        .get("geo_work_budget")
        .and_then(toml::Value::as_table)
        .ok_or("no [geo_work_budget] in the record")?;
    let bound = int(budget, "worst_case_instructions")?;
    // The heaviest of the GEO worst cases kept in fixtures/worst-case/ (the slowest found by
    // M7 instructions, and one that runs to the whole budget).
    let mut heaviest = 0;
    for name in [
        "geo-16-clients-0p7deg-200d-west",
        "geo-16-clients-full-budget",
    ] {
        heaviest = heaviest.max(int(named(&geo, name)?, "instructions")?);
    }
    line(
        &mut md,
        "M7: GEO tour, any request within the limits (budget × kernels' largest instructions per unit)",
        "≤ 400 M instructions",
        &format!(
            "≤ {} by the kernels measured in CI; heaviest found {}",
            mega(bound),
            mega(heaviest)
        ),
        bound <= 400_000_000 && heaviest <= bound,
        "[geo-tour](docs/geo-tour.md)",
    );
    let arc = named(&leo_fixtures, "leo-tour-example1-single-arc")?;
    let order = named(&leo_fixtures, "leo-tour-example1-sequence/order")?;
    let onboard = named(&leo_fixtures, "leo-tour-example1-sequence")?;
    let (arc_n, order_n, onboard_n) = (
        int(arc, "instructions")?,
        int(order, "instructions")?,
        int(onboard, "instructions")?,
    );
    line(
        &mut md,
        "M7: LEO tour, one arc / the sequencing (any request: budget × 100 per unit) / Example I's on-board part (order + 4 arcs)",
        "≤ 400 M instructions a request",
        &format!(
            "{} / {} / {} summed, stack {} / {} B",
            mega(arc_n),
            mega(order_n),
            giga(onboard_n),
            grouped(int(arc, "stack_bytes")?),
            grouped(int(onboard, "stack_bytes")?)
        ),
        arc_n.max(order_n) <= 400_000_000,
        "[leo-tour](docs/leo-tour.md)",
    );
    Ok(md)
}

/// The README with its generated lines replaced by what the records on disk generate.
///
/// # Errors
/// A file cannot be read, does not parse, or the markers are missing.
pub fn expected_readme() -> Result<(String, String), String> {
    let read =
        |file: &str| std::fs::read_to_string(root().join(file)).map_err(|e| format!("{file}: {e}"));
    let readme = read(README_FILE)?;
    let generated = render_readme(&read(RECORD_FILE)?, &read(LEO_RECORD_FILE)?)?;
    let expected = splice_between(&readme, README_BEGIN, README_END, &generated)?;
    Ok((readme, expected))
}

/// Rewrite the README's generated lines from the records on disk; returns whether they changed.
///
/// # Errors
/// As [`expected_readme`], or the README cannot be written.
pub fn update_readme() -> Result<bool, String> {
    let (readme, expected) = expected_readme()?;
    if readme == expected {
        return Ok(false);
    }
    std::fs::write(root().join(README_FILE), expected)
        .map_err(|e| format!("{README_FILE}: {e}"))?;
    Ok(true)
}

/// Start marker of the README's lines generated from `fixtures/golden/figures/`.
pub const FIGURES_BEGIN: &str =
    "<!-- readme-figures:begin (generated from fixtures/golden/figures/*.toml; do not edit) -->";
/// End marker of those lines.
pub const FIGURES_END: &str = "<!-- readme-figures:end -->";

/// The README's order of the figure records (`fixtures/golden/figures/NAME.toml`); every
/// record is listed once, and every listed name has a record.
pub const FIGURE_ORDER: [&str; 29] = [
    "a-paper-case-cost",
    "a-dynamics-error",
    "a-square-swap",
    "a-wall-time",
    "a-oracle-families",
    "a-held-out",
    "a-held-out-oracle",
    "b-min-norm",
    "b-least-fuel-search",
    "b-exact-vs-clarabel",
    "b-timing",
    "geo-60-day-allocation",
    "geo-brute-published",
    "geo-brute-small-tours",
    "geo-brute-held-out",
    "geo-timing",
    "leo-example-one",
    "leo-sequencing-on-board",
    "leo-full-plans",
    "leo-held-out-tours",
    "leo-arc-oracle",
    "leo-on-board-host",
    "truth-vs-scipy",
    "c-interface",
    "harness-demo",
    "harness-flood-abandon",
    "harness-flood-read",
    "harness-flood-ignore",
    "heap-allocations",
];

/// The README's lines of every figure record, in [`FIGURE_ORDER`]; an error names a record
/// that is missing or not listed.
pub fn figure_lines() -> Result<String, String> {
    use reconfig_host::figure_record::{load, names};
    let stored = names()?;
    for name in &stored {
        if !FIGURE_ORDER.contains(&name.as_str()) {
            return Err(format!(
                "figure record {name} is not in readme_figures::FIGURE_ORDER"
            ));
        }
    }
    let mut md = String::new();
    for name in FIGURE_ORDER {
        let _ = writeln!(md, "{}", load(name)?.readme_line());
    }
    Ok(md)
}

/// `docs/firmware.md`'s table of the LEO image's requests, from the LEO record: the paper's
/// single arc, Example I's on-board part summed, its sequencing request and its four arcs.
pub fn leo_image_table(leo_record: &str) -> Result<String, String> {
    let leo = parse(leo_record, LEO_RECORD_FILE)?;
    let fixtures = entries(&leo, "leo_fixture");
    let at_400_mhz = |instructions: u64| format!("about {:.2} s", instructions as f64 / 400e6);
    let kb = |bytes: u64| format!("{:.1} KB", bytes as f64 / 1e3);
    let g3 = |v: u64| format!("{:.3} G", v as f64 / 1e9);
    let per_unit = |e: &Entry| -> Result<String, String> {
        let (n, units) = (int(e, "instructions")?, int(e, "work_units")?);
        Ok(format!(
            "{} ({} work units, {:.1} instructions per unit)",
            g3(n),
            grouped(units),
            n as f64 / units.max(1) as f64
        ))
    };
    let single = named(&fixtures, "leo-tour-example1-single-arc")?;
    let summed = named(&fixtures, "leo-tour-example1-sequence")?;
    let order = named(&fixtures, "leo-tour-example1-sequence/order")?;
    let mut arcs = Vec::new();
    for k in 1..=4 {
        arcs.push(named(
            &fixtures,
            &format!("leo-tour-example1-sequence/arc-{k}"),
        )?);
    }
    let mut md =
        String::from("| | instructions | at 400 MHz | stack |\n| --- | --- | --- | --- |\n");
    let _ = writeln!(
        md,
        "| the paper's single arc (one request) | **{}** | {} | {} |",
        per_unit(single)?,
        at_400_mhz(int(single, "instructions")?),
        kb(int(single, "stack_bytes")?)
    );
    let _ = writeln!(
        md,
        "| Example I's on-board part, summed: | **{}** | {} | {} (the largest request's) |",
        giga(int(summed, "instructions")?),
        at_400_mhz(int(summed, "instructions")?),
        kb(int(summed, "stack_bytes")?)
    );
    let _ = writeln!(
        md,
        "| · the sequencing request | {} | {} | {} |",
        per_unit(order)?,
        at_400_mhz(int(order, "instructions")?),
        kb(int(order, "stack_bytes")?)
    );
    let mut arc_instructions = Vec::new();
    let (mut arcs_sum, mut arc_stack) = (0u64, 0u64);
    for a in &arcs {
        let n = int(a, "instructions")?;
        arc_instructions.push(format!("{:.3}", n as f64 / 1e9));
        arcs_sum += n;
        arc_stack = arc_stack.max(int(a, "stack_bytes")?);
    }
    let _ = writeln!(
        md,
        "| · the four arc requests of its order | {} G | {} | {} each at most |",
        arc_instructions.join(" / "),
        at_400_mhz(arcs_sum),
        kb(arc_stack)
    );
    Ok(md)
}
