//! Q5 benchmarks.
//!
//! - divan: the grammar table (all cells, both light kinds) and the radiosity form factors of the
//!   Cornell-like box at 2 × 2 and 4 × 4 patches per quad.
//! - `cargo bench -p hw3-benches --bench q5_radiosity` also measures radiosity's accuracy against time: the
//!   colour-bleeding and ambient-glow values for 1…8 patches per quad edge, against the path-traced
//!   reference, with the wall time of form factors plus solve; writes
//!   `docs/data/q5_radiosity_accuracy.md` and `.csv`. `cargo test --benches` runs each divan bench
//!   once and skips that measurement.
//! - It also measures the solvers' iterations against seconds on the 6 × 6 box: sweeps and wall
//!   time (solve only; the form factors are shared) for each solver to bring the relative error
//!   below 10⁻², 10⁻⁴ and 10⁻⁶ of a Gauss–Seidel solution run to convergence; writes
//!   `docs/data/q5_radiosity_solvers.md` and `.csv`.

use hw3::q5_effect_tables::experiments::{Measured, bleeding, cornell_system, glow};
use hw3::q5_effect_tables::radiosity::{Solver, relative_errors};
use hw3::q5_effect_tables::{Budget, grammar_table};
use std::fmt::Write as _;
use std::time::Instant;

fn main() {
    if std::env::args().any(|a| a == "--bench") {
        write_accuracy_table();
        write_solver_table();
    }
    divan::main();
}

#[divan::bench]
fn grammar_table_all_cells() -> usize {
    grammar_table().expect("built-in languages").len()
}

#[divan::bench(args = [2, 4])]
fn radiosity_form_factors_and_solve(subdivisions: usize) -> usize {
    let (_, system) = cornell_system(subdivisions, 2).expect("built-in scene");
    system.solve(Solver::GaussSeidel, 40).len()
}

const LEVELS: [usize; 5] = [1, 2, 4, 6, 8];

fn write_accuracy_table() {
    let published = &Budget::PUBLISHED;
    let reference = (
        bleeding(Measured::PathTracing, published).expect("reference"),
        glow(Measured::PathTracing, published).expect("reference"),
    );
    let mut csv = String::from("subdivisions,patches,seconds,bleeding,glow,bleeding_error,glow_error\n");
    let mut table = format!(
        "Reference (path tracing): bleeding {:.4}, glow {:.4}. Radiosity with 2 × 2 form-factor samples per patch; seconds = form factors + 60 Gauss–Seidel sweeps for one scene.\n\n| patches per edge | patches | seconds | bleeding | error | glow | error |\n|---|---|---|---|---|---|---|\n",
        reference.0, reference.1
    );
    for n in LEVELS {
        let method = Measured::Radiosity { subdivisions: n, samples: 2 };
        let start = Instant::now();
        let (_, system) = cornell_system(n, 2).expect("built-in scene");
        let _ = system.solve(Solver::GaussSeidel, 60);
        let seconds = start.elapsed().as_secs_f64();
        let patches = system.mesh.patches.len();
        let (b, g) = (bleeding(method, published).expect("mesh"), glow(method, published).expect("mesh"));
        let (eb, eg) = ((b / reference.0 - 1.0).abs(), (g / reference.1 - 1.0).abs());
        let _ = writeln!(csv, "{n},{patches},{seconds:.4e},{b:.4e},{g:.4e},{eb:.4e},{eg:.4e}");
        let _ = writeln!(table, "| {n} | {patches} | {seconds:.3e} | {b:.4} | {eb:.3} | {g:.4} | {eg:.3} |");
    }
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/data");
    std::fs::create_dir_all(data).expect("docs/data is writable");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q5_radiosity_accuracy.csv")), csv.as_bytes())
        .expect("write the CSV");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q5_radiosity_accuracy.md")), table.as_bytes())
        .expect("write the table");
}

/// The error levels the solver table reports.
const TOLERANCES: [f64; 3] = [1e-2, 1e-4, 1e-6];

fn write_solver_table() {
    let (_, system) = cornell_system(6, 2).expect("built-in scene");
    let converged = system.solve(Solver::GaussSeidel, 400).pop().expect("a history");
    let patches = system.mesh.patches.len();
    let mut csv = String::from("solver,tolerance,sweeps,seconds\n");
    let mut table = format!(
        "Cornell-like box, 6 × 6 patches per quad ({patches} patches); error = max |B − B*| / max B* against Gauss–Seidel \
         after 400 sweeps; seconds = the solve alone as `System::solve` runs it, keeping every sweep for the plots (best of 5; form factors excluded); a progressive sweep is {patches} shots.\n\n\
         | solver | sweeps to 1e-2 | seconds | sweeps to 1e-4 | seconds | sweeps to 1e-6 | seconds |\n|---|---|---|---|---|---|---|\n"
    );
    for solver in Solver::ALL {
        let errors = relative_errors(&system.solve(solver, 200), &converged);
        let mut row = format!("| {} |", solver.name());
        for tolerance in TOLERANCES {
            match errors.iter().position(|&e| e < tolerance) {
                Some(sweeps) => {
                    let seconds = (0..5)
                        .map(|_| {
                            let start = Instant::now();
                            std::hint::black_box(system.solve(solver, sweeps));
                            start.elapsed().as_secs_f64()
                        })
                        .fold(f64::INFINITY, f64::min);
                    let _ = writeln!(csv, "{},{tolerance:e},{sweeps},{seconds:.4e}", solver.name());
                    let _ = write!(row, " {sweeps} | {seconds:.3e} |");
                }
                None => {
                    let _ = writeln!(csv, "{},{tolerance:e},-,-", solver.name());
                    row.push_str(" > 200 | – |");
                }
            }
        }
        table.push_str(&row);
        table.push('\n');
    }
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/data");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q5_radiosity_solvers.csv")), csv.as_bytes())
        .expect("write the CSV");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q5_radiosity_solvers.md")), table.as_bytes())
        .expect("write the table");
}
