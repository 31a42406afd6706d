//! The checked-in header `capi/include/reconfig.h` is what cbindgen makes of `capi/src` with
//! `capi/cbindgen.toml`. Set `RECONFIG_UPDATE_HEADER=1` to rewrite it.
#![allow(clippy::expect_used, clippy::panic)]

use std::path::PathBuf;

#[test]
fn checked_in_header_matches_cbindgen() {
    let crate_dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml"))
        .expect("capi/cbindgen.toml parses");
    let bindings = cbindgen::Builder::new()
        .with_crate(&crate_dir)
        .with_config(config)
        .generate()
        .expect("cbindgen parses capi/src");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let generated = String::from_utf8(generated).expect("cbindgen writes UTF-8");
    let path = crate_dir.join("include/reconfig.h");
    if std::env::var_os("RECONFIG_UPDATE_HEADER").is_some() {
        std::fs::write(&path, &generated).expect("write capi/include/reconfig.h");
        return;
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    if checked_in != generated {
        let first = checked_in
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| checked_in.lines().count().min(generated.lines().count()));
        let line = |text: &str| {
            text.lines()
                .nth(first)
                .unwrap_or("<end of file>")
                .to_owned()
        };
        panic!(
            "capi/include/reconfig.h is stale: an exported type or function changed without \
             regenerating the header.\nfirst difference at line {}:\n  checked in: {}\n  generated:  {}\n\
             regenerate with: RECONFIG_UPDATE_HEADER=1 cargo test -p reconfig-capi --test header",
            first + 1,
            line(&checked_in),
            line(&generated),
        );
    }
}
