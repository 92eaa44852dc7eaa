//! Whether this machine runs the instructions flexdem was compiled for.
//!
//! The workspace builds for the CPU it is built on (`target-cpu=native` in
//! `.cargo/config.toml`): on an x86-64 with AVX2 the links'
//! and the particles' four lanes take one instruction where two were needed, and the
//! scalar code three-operand forms; about a fifth less time per step (`bench/README.md`).
//! No fused multiply–add is made (Rust never contracts `a·b + c`), and every operation is
//! the same IEEE one: on a given machine, results are bit-identical to a portable build's
//! (the libm functions, `sin_cos` and `atan2`, come from the system's library either way).
//!
//! A binary copied to a machine without those instructions would stop on the first one with
//! `SIGILL`; the command line and the Python module call [`unsupported_features`] first and
//! say what is missing and how to rebuild instead.

/// The instruction-set extensions this binary was compiled to use that this machine lacks
/// (empty where it has them all, and on other architectures).
pub fn unsupported_features() -> Vec<&'static str> {
    let mut missing = Vec::new();
    #[cfg(target_arch = "x86_64")]
    {
        macro_rules! check {
            ($($feature:tt),* $(,)?) => {
                $(
                    if cfg!(target_feature = $feature)
                        && !std::arch::is_x86_feature_detected!($feature)
                    {
                        missing.push($feature);
                    }
                )*
            };
        }
        // every extension `target-cpu=native` may enable that the compiler can emit code for
        // (a machine with AVX-512 of one generation would otherwise pass the check on
        // another's and stop on an instruction of the newer one)
        check!(
            "sse3",
            "ssse3",
            "sse4.1",
            "sse4.2",
            "popcnt",
            "avx",
            "avx2",
            "fma",
            "bmi1",
            "bmi2",
            "lzcnt",
            "movbe",
            "f16c",
            "adx",
            "aes",
            "pclmulqdq",
            "sha",
            "gfni",
            "vaes",
            "vpclmulqdq",
            "avx512f",
            "avx512bw",
            "avx512cd",
            "avx512dq",
            "avx512vl",
            "avx512ifma",
            "avx512vbmi",
            "avx512vbmi2",
            "avx512bitalg",
            "avx512vpopcntdq",
            "avx512vnni",
            "avx512bf16",
        );
    }
    missing
}

/// The message for [`unsupported_features`]' `missing`: what is missing, and the two ways to
/// get a binary that runs (None when nothing is missing).
pub fn unsupported_message(missing: &[&str]) -> Option<String> {
    if missing.is_empty() {
        return None;
    }
    Some(format!(
        "this flexdem was compiled for a CPU with {}, which this machine lacks (a binary \
         built on another machine?): build it on this machine (`cargo build --release`, \
         which compiles for the CPU it runs on), or for any x86-64 with \
         RUSTFLAGS=\"-C target-cpu=x86-64\" (the same results, bit for bit, a fifth slower)",
        missing.join(", ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_machine_that_built_the_tests_runs_them() {
        // the tests run where they were built: nothing can be missing
        assert_eq!(unsupported_features(), Vec::<&str>::new());
        assert_eq!(unsupported_message(&[]), None);
    }

    #[test]
    fn the_message_names_what_is_missing_and_both_fixes() {
        let m = unsupported_message(&["avx2", "fma"]).unwrap();
        assert!(m.contains("avx2, fma"), "{m}");
        assert!(m.contains("cargo build --release"), "{m}");
        assert!(m.contains("target-cpu=x86-64"), "{m}");
    }
}
