//! `x86_simd`: the kd-tree's vector code (SSE2, and AVX2 and AVX-512 chosen at run time) is
//! compiled on x86-64 unless the `portable` feature asks for the scalar code every other target
//! runs, so that an x86-64 machine can test that code too.

fn main() {
    println!("cargo::rustc-check-cfg=cfg(x86_simd)");
    println!("cargo::rerun-if-changed=build.rs");
    let x86_64 = std::env::var("CARGO_CFG_TARGET_ARCH").is_ok_and(|arch| arch == "x86_64");
    if x86_64 && std::env::var_os("CARGO_FEATURE_PORTABLE").is_none() {
        println!("cargo::rustc-cfg=x86_simd");
    }
}
