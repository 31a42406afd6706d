//! Fused multiply-add would break bit-identity with the host (which never fuses): the images'
//! disassembly must hold none.

use std::path::Path;
use std::process::Command;

use crate::prerequisites::skip;

/// Disassemble `elf` and fail on any `vfma`-family instruction, naming the function; skip (or
/// fail under `RECONFIG_REQUIRE_QEMU=1`) without `arm-none-eabi-objdump`.
pub fn assert_no_fused_multiply_add(test: &str, elf: &Path) {
    let output = match Command::new("arm-none-eabi-objdump")
        .arg("-d")
        .arg(elf)
        .output()
    {
        Ok(o) if o.status.success() => o,
        _ => {
            skip(
                test,
                "arm-none-eabi-objdump is not installed. Install it with \
                 `sudo apt-get install binutils-arm-none-eabi`.",
            );
            return;
        }
    };
    let mut function = String::new();
    let mut fused = Vec::new();
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        if line.ends_with(">:") {
            function = line.to_owned();
        }
        let mnemonic = line.split('\t').nth(2).unwrap_or("").trim();
        if ["vfma", "vfms", "vfnma", "vfnms"]
            .iter()
            .any(|m| mnemonic.starts_with(m))
        {
            fused.push(format!("{function} {}", line.trim()));
        }
    }
    assert!(
        fused.is_empty(),
        "fused multiply-add in {} breaks bit-identity with the host:\n{}",
        elf.display(),
        fused.join("\n")
    );
}
