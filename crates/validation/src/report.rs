//! What a case reports: checks against expected values, figures, informative values, and how
//! they are written as Markdown.

use std::fmt::Write as _;
use std::path::PathBuf;

/// Where and how a case runs.
#[derive(Clone, Debug)]
pub struct Context {
    /// Folder the report and its plots are written to (already created).
    pub out_dir: PathBuf,
    /// True for the fast subset run by `cargo test` (shorter runs, coarser meshes, looser but
    /// stated tolerances are NOT allowed: a quick run checks the same quantities; it may check
    /// fewer of them).
    pub quick: bool,
}

/// How far a measured value may be from the expected one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tolerance {
    /// |measured − expected| / |expected| at most this.
    Relative(f64),
    /// |measured − expected| at most this (in the check's unit).
    Absolute(f64),
}

/// One measured quantity against its expected value.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    /// What is measured: "tip deflection", "contact time", ...
    pub quantity: String,
    /// Its unit: "m", "s", "" (dimensionless), ...
    pub unit: String,
    /// The expected value.
    pub expected: f64,
    /// The measured value.
    pub measured: f64,
    /// How close `measured` must be to `expected`.
    pub tolerance: Tolerance,
    /// Where `expected` comes from: "P·L³/(3EI)", "YADE 2023.02a", "eq 18", ...
    pub source: String,
}

impl Check {
    /// A check with a relative tolerance `tol`.
    pub fn relative(
        quantity: &str,
        unit: &str,
        expected: f64,
        measured: f64,
        tol: f64,
        source: &str,
    ) -> Check {
        Check {
            quantity: quantity.into(),
            unit: unit.into(),
            expected,
            measured,
            tolerance: Tolerance::Relative(tol),
            source: source.into(),
        }
    }

    /// A check with an absolute tolerance `tol` (in `unit`).
    pub fn absolute(
        quantity: &str,
        unit: &str,
        expected: f64,
        measured: f64,
        tol: f64,
        source: &str,
    ) -> Check {
        Check {
            quantity: quantity.into(),
            unit: unit.into(),
            expected,
            measured,
            tolerance: Tolerance::Absolute(tol),
            source: source.into(),
        }
    }

    /// The error as the tolerance measures it: |measured − expected| / |expected| for a
    /// relative tolerance (infinite when expected is 0 and measured is not), |measured −
    /// expected| for an absolute one. NaN when either value is not finite.
    pub fn error(&self) -> f64 {
        if !self.expected.is_finite() || !self.measured.is_finite() {
            return f64::NAN;
        }
        let difference = (self.measured - self.expected).abs();
        match self.tolerance {
            Tolerance::Relative(_) if difference == 0.0 => 0.0,
            Tolerance::Relative(_) => difference / self.expected.abs(),
            Tolerance::Absolute(_) => difference,
        }
    }

    /// True when both values are finite and the error is within the tolerance.
    pub fn passed(&self) -> bool {
        let limit = match self.tolerance {
            Tolerance::Relative(t) | Tolerance::Absolute(t) => t,
        };
        let error = self.error();
        error.is_finite() && error <= limit
    }
}

/// A PNG figure of a case.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// PNG file name inside [`Context::out_dir`].
    pub file: String,
    /// What it shows.
    pub caption: String,
}

/// The result of one case.
#[derive(Clone, Debug, PartialEq)]
pub struct CaseReport {
    /// Short identifier: "catenary", "brazier", "impact_solid", ...
    pub id: String,
    /// Title of its report section.
    pub title: String,
    /// Markdown: geometry, materials, loads, dt, steps, link mode, what is measured.
    pub setup: String,
    /// The checks; the case passes when all pass.
    pub checks: Vec<Check>,
    /// Its figures.
    pub figures: Vec<Figure>,
    /// Markdown: anything a reader must know (why a check is informative only, ...).
    pub notes: String,
    /// Extra measured values shown but not checked: (name, value text).
    pub informative: Vec<(String, String)>,
}

impl CaseReport {
    /// An empty report of case `id` titled `title`, to be filled in.
    pub fn new(id: &str, title: &str) -> CaseReport {
        CaseReport {
            id: id.into(),
            title: title.into(),
            setup: String::new(),
            checks: Vec::new(),
            figures: Vec::new(),
            notes: String::new(),
            informative: Vec::new(),
        }
    }

    /// True when every check passes (a report without checks passes).
    pub fn passed(&self) -> bool {
        self.checks.iter().all(Check::passed)
    }

    /// Number of checks that pass.
    pub fn checks_passed(&self) -> usize {
        self.checks.iter().filter(|c| c.passed()).count()
    }

    /// Adds an informative value `name` shown as `value`.
    pub fn inform(&mut self, name: &str, value: impl Into<String>) {
        self.informative.push((name.into(), value.into()));
    }

    /// The Markdown table of the checks.
    pub fn checks_table(&self) -> String {
        let mut s = String::new();
        s.push_str("| quantity | expected | measured | error | tolerance | result | source |\n");
        s.push_str("|---|---|---|---|---|---|---|\n");
        for c in &self.checks {
            let unit = if c.unit.is_empty() { String::new() } else { format!(" {}", c.unit) };
            let (error, tolerance) = match c.tolerance {
                Tolerance::Relative(t) => {
                    (format_number(c.error()), format!("{} rel.", format_number(t)))
                }
                Tolerance::Absolute(t) => (
                    format!("{}{unit}", format_number(c.error())),
                    format!("{}{unit} abs.", format_number(t)),
                ),
            };
            let _ = writeln!(
                s,
                "| {} | {}{unit} | {}{unit} | {error} | {tolerance} | {} | {} |",
                escape(&c.quantity),
                format_number(c.expected),
                format_number(c.measured),
                if c.passed() { "pass" } else { "**FAIL**" },
                escape(&c.source),
            );
        }
        s
    }

    /// The report section of this case (heading level 2), figures linked relative to the
    /// report's folder.
    pub fn to_markdown(&self) -> String {
        let mut s = String::new();
        let verdict = if self.passed() { "pass" } else { "FAIL" };
        let _ = writeln!(s, "## {} (`{}`): {verdict}\n", self.title, self.id);
        if !self.setup.trim().is_empty() {
            let _ = writeln!(s, "**Setup.** {}\n", self.setup.trim());
        }
        if !self.checks.is_empty() {
            s.push_str(&self.checks_table());
            s.push('\n');
        }
        if !self.informative.is_empty() {
            s.push_str("Informative values (not checked):\n\n");
            for (name, value) in &self.informative {
                let _ = writeln!(s, "- {name}: {value}");
            }
            s.push('\n');
        }
        for f in &self.figures {
            let _ = writeln!(s, "![{}]({})\n\n*{}*\n", escape(&f.caption), f.file, f.caption);
        }
        if !self.notes.trim().is_empty() {
            let _ = writeln!(s, "**Notes.** {}\n", self.notes.trim());
        }
        s
    }
}

/// A number with 6 significant digits, in scientific notation when small or large.
pub fn format_number(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 {
        return "0".into();
    }
    let magnitude = v.abs().log10().floor() as i32;
    if (-3..6).contains(&magnitude) {
        let decimals = (5 - magnitude).max(0) as usize;
        let text = format!("{v:.decimals$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            text
        }
    } else {
        let text = format!("{v:.5e}");
        match text.split_once('e') {
            Some((mantissa, exponent)) if mantissa.contains('.') => {
                format!("{}e{exponent}", mantissa.trim_end_matches('0').trim_end_matches('.'))
            }
            _ => text,
        }
    }
}

/// `text` with the Markdown table separator escaped.
fn escape(text: &str) -> String {
    text.replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_and_absolute_errors() {
        let c = Check::relative("x", "m", 2.0, 2.01, 0.01, "-");
        assert!((c.error() - 0.005).abs() < 1e-12);
        assert!(c.passed());
        let c = Check::relative("x", "m", 2.0, 2.1, 0.01, "-");
        assert!(!c.passed());
        let c = Check::absolute("x", "m", 0.0, 0.001, 0.002, "-");
        assert!((c.error() - 0.001).abs() < 1e-15 && c.passed());
        let c = Check::relative("x", "m", 0.0, 0.0, 0.0, "-");
        assert!(c.passed());
    }

    #[test]
    fn a_non_finite_measurement_fails() {
        assert!(!Check::relative("x", "", 1.0, f64::NAN, 1e9, "-").passed());
        assert!(!Check::absolute("x", "", 1.0, f64::INFINITY, 1e9, "-").passed());
        let mut r = CaseReport::new("a", "A");
        assert!(r.passed());
        r.checks.push(Check::relative("x", "", 1.0, f64::NAN, 1.0, "-"));
        assert!(!r.passed() && r.to_markdown().contains("**FAIL**"));
    }

    #[test]
    fn numbers_are_short() {
        assert_eq!(format_number(1.0), "1");
        assert_eq!(format_number(0.8164966), "0.816497");
        assert_eq!(format_number(508.4), "508.4");
        assert_eq!(format_number(3.1830989e-4), "3.1831e-4");
        assert_eq!(format_number(1e-6), "1e-6");
        assert_eq!(format_number(-2.5e7), "-2.5e7");
    }
}
