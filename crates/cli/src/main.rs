//! The `flexdem` command (to come: `run`, `check`, `info`, `resume`).

fn main() {
    eprintln!(
        "flexdem {}: the command line is not built yet; the engine is used as a Rust library for now.",
        env!("CARGO_PKG_VERSION")
    );
    std::process::exit(2);
}
