//! Build script: turns on the x86-64 SIMD paths of the frequency response (`cfg(ltikit_simd)`,
//! `src/analysis/factored/bode/{avx2,avx512}.rs`) when the compiler has what they need
//! stable — safe `#[target_feature]` functions (rustc 1.86) and the AVX-512 intrinsics (1.89).
//! Older compilers (the crate's `rust-version` is 1.85) build the portable loop only, with the
//! same results.

use std::process::Command;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(ltikit_simd)");
    println!("cargo:rerun-if-changed=build.rs");
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let minor = Command::new(rustc)
        .arg("--version")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .and_then(|v| {
            // "rustc 1.95.0 (…)": the minor version
            let version = v.split_whitespace().nth(1)?.to_owned();
            version.split('.').nth(1)?.parse::<u32>().ok()
        });
    if minor.is_some_and(|m| m >= 89) {
        println!("cargo:rustc-cfg=ltikit_simd");
    }
}
