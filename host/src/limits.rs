//! Limits files (`serve --limits FILE`, `solve --limits FILE`, `feed --limits FILE`) and
//! fixture `[settings]` tables, both read as partial TOML tables over the core's defaults.
//!
//! A limits file has `[pseudospectral]`, `[impulsive]`, `[geo_tour]` and `[leo_tour]` tables
//! whose keys are the problem sizes of `reconfig_core::limits::{pseudospectral, impulsive,
//! geo_tour, leo_tour}::Limits` and the settings' own names (a setting's limit is written as the
//! setting; its settings table says whether it is a ceiling or a floor). A setting may also be
//! written in the planner's nested table (`[impulsive.settings]`, `[leo_tour.arc]`,
//! `[leo_tour.sequence]`). Keys left out keep the built-in limit; unknown keys are an error.

use anyhow::{anyhow, Context, Result};
use reconfig_core::limits::Limits;
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// `--limits FILE` of the commands that apply limits.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct LimitsArg {
    /// Limits file (TOML; default: the built-in limits, docs/harness.md). A request outside
    /// them is refused with `LimitExceeded`, naming the setting, its value and the limit.
    #[arg(long = "limits", value_name = "FILE")]
    pub limits: Option<PathBuf>,
}

impl LimitsArg {
    /// The limits from the file, or the built-in ones.
    ///
    /// # Errors
    /// The file cannot be read or does not parse.
    pub fn load(&self) -> Result<Limits> {
        self.limits.as_deref().map_or(Ok(Limits::default()), load)
    }
}

/// Read a limits file.
///
/// # Errors
/// The file cannot be read, is not TOML, or has an unknown key or a wrong type.
pub fn load(path: &Path) -> Result<Limits> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read limits file {}", path.display()))?;
    parse(&text).with_context(|| format!("in limits file {}", path.display()))
}

/// Parse limits text.
///
/// # Errors
/// Not TOML, an unknown key or a wrong type.
pub fn parse(text: &str) -> Result<Limits> {
    let file: toml::Table = toml::from_str(text).map_err(|e| anyhow!("{e}"))?;
    let mut merged = toml::Table::try_from(Limits::default()).context("cannot tabulate")?;
    for (planner, table) in file {
        let Some(toml::Value::Table(slot)) = merged.get_mut(&planner) else {
            let known: Vec<&str> = merged.keys().map(String::as_str).collect();
            return Err(anyhow!(
                "unknown planner table [{planner}]; known: {}",
                known.join(", ")
            ));
        };
        let toml::Value::Table(table) = table else {
            return Err(anyhow!("[{planner}] is not a table"));
        };
        merge_planner(&planner, slot, table)?;
    }
    merged
        .try_into()
        .map_err(|e| anyhow!("bad value in the limits file: {e}"))
}

/// Merge one planner's table: a key of the planner's own (a size, or a nested settings table)
/// replaces it; any other key must be a setting of exactly one nested settings table.
fn merge_planner(planner: &str, slot: &mut toml::Table, table: toml::Table) -> Result<()> {
    for (key, value) in table {
        match (slot.get_mut(&key), value) {
            (Some(toml::Value::Table(nested)), toml::Value::Table(given)) => {
                for (k, v) in given {
                    if !nested.contains_key(&k) {
                        return Err(anyhow!("unknown setting {k:?} in [{planner}.{key}]"));
                    }
                    nested.insert(k, v);
                }
            }
            (Some(old), value) => *old = value,
            (None, value) => {
                let owners: Vec<String> = slot
                    .iter()
                    .filter(|(_, v)| v.as_table().is_some_and(|t| t.contains_key(&key)))
                    .map(|(name, _)| name.clone())
                    .collect();
                match (
                    owners.as_slice(),
                    owners.first().and_then(|o| slot.get_mut(o)),
                ) {
                    ([_], Some(toml::Value::Table(nested))) => {
                        nested.insert(key, value);
                    }
                    _ => return Err(anyhow!("unknown limit {key:?} in [{planner}]")),
                }
            }
        }
    }
    Ok(())
}

/// The built-in limits as a TOML file (every key), for documentation and as a template.
///
/// # Errors
/// Never in practice (the limits are plain numbers and flags).
pub fn default_toml() -> Result<String> {
    Ok(toml::to_string(&Limits::default())?)
}

/// Overlay a partial `[settings]` table on `defaults`: every key must be a field of `T` (the
/// core's setting names), and keys left out keep the default.
///
/// # Errors
/// An unknown key (named) or a value of the wrong type.
pub fn overlay<T: Serialize + DeserializeOwned>(defaults: &T, table: &toml::Table) -> Result<T> {
    let mut merged = toml::Table::try_from(defaults).context("cannot tabulate the defaults")?;
    for (key, value) in table {
        if !merged.contains_key(key) {
            let known: Vec<&str> = merged.keys().map(String::as_str).collect();
            return Err(anyhow!(
                "unknown setting {key:?} in [settings]; known: {}",
                known.join(", ")
            ));
        }
        merged.insert(key.clone(), value.clone());
    }
    merged
        .try_into()
        .map_err(|e| anyhow!("bad value in [settings]: {e}"))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use reconfig_core::{impulsive, pseudospectral};

    #[test]
    fn partial_files_keep_the_rest_and_unknown_keys_fail() {
        let l = parse("[impulsive]\nsearch_samples = 500\n").unwrap();
        assert_eq!(l.impulsive.settings.search_samples, 500);
        assert_eq!(l.pseudospectral, Limits::default().pseudospectral);
        assert_eq!(
            l.impulsive.settings.fixed_point_max_iter,
            Limits::default().impulsive.settings.fixed_point_max_iter
        );
        let nested = parse("[impulsive.settings]\nsearch_samples = 500\n").unwrap();
        assert_eq!(nested, l);
        assert!(parse("[impulsive]\nsearch_sample = 500\n").is_err());
        let l = parse("[leo_tour]\nhop_rounds = 2\nmax_arcs = 10\n").unwrap();
        assert_eq!(l.leo_tour.arc.hop_rounds, 2);
        assert_eq!(l.leo_tour.sequence.max_arcs, 10);
        assert_eq!(
            l.leo_tour.arc.grid_points,
            Limits::default().leo_tour.arc.grid_points
        );
        assert!(
            parse("[leo_tour]\nimpulses = 3\n")
                .unwrap()
                .leo_tour
                .impulses
                == 3
        );
        assert!(parse("[nonsense]\nx = 1\n").is_err());
        assert!(parse("[leo_tour]\nhop_round = 2\n").is_err());
        assert!(parse("[pseudospectral]\nsqp_max_iter = -1\n").is_err());
        let round = parse(&default_toml().unwrap()).unwrap();
        assert_eq!(round, Limits::default());
    }

    #[test]
    fn limit_names_are_the_settings_names() {
        // A limits file and a fixture's [settings] use one vocabulary: the settings table's
        // names, each setting once.
        use std::collections::BTreeSet;
        fn same<'a>(settings: impl Serialize, names: impl Iterator<Item = &'a str>) {
            let table = toml::Table::try_from(settings).unwrap();
            let keys: BTreeSet<&str> = table.keys().map(String::as_str).collect();
            assert_eq!(keys, names.collect::<BTreeSet<_>>());
        }
        same(
            pseudospectral::Settings::default(),
            pseudospectral::SettingId::ALL.iter().map(|id| id.name()),
        );
        same(
            impulsive::Settings::default(),
            impulsive::SettingId::ALL.iter().map(|id| id.name()),
        );
    }

    #[test]
    fn settings_tables_overlay_the_defaults() {
        let t: toml::Table = toml::from_str("search_samples = 2000000\nmin_fuel = false").unwrap();
        let s = overlay(&impulsive::Settings::default(), &t).unwrap();
        assert_eq!(s.search_samples, 2_000_000);
        assert!(!s.min_fuel);
        assert_eq!(
            s.kepler_max_iter,
            impulsive::Settings::default().kepler_max_iter
        );
        let t: toml::Table = toml::from_str("sqp_max_iters = 3").unwrap();
        let e = overlay(&pseudospectral::Settings::default(), &t).unwrap_err();
        assert!(e.to_string().contains("sqp_max_iters"), "{e}");
    }
}
