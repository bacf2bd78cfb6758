//! `hw3`: prints every answer and regenerates every figure; subcommands compute single answers.
//!
//! Exit status: 0 on success, 2 on invalid input (one line on stderr, nothing written),
//! 1 on an internal failure (for example a figure that cannot be written).

use anyhow::Context as _;
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "hw3", version, about = "Ray-tracing homework 3: answers, figures and checks")]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Print the answers (all questions, or one).
    Answers {
        /// Only this question (q1 … q5).
        #[arg(long)]
        question: Option<String>,
    },
    /// Q2: intersect one ray with one sphere (hit, point, normal, reflection, closest approach).
    Sphere {
        /// Eye point e, as X,Y,Z.
        #[arg(long, allow_hyphen_values = true)]
        origin: String,
        /// Direction d, as X,Y,Z (any non-zero length).
        #[arg(long, allow_hyphen_values = true)]
        dir: String,
        /// Sphere centre o, as X,Y,Z.
        #[arg(long, allow_hyphen_values = true)]
        center: String,
        /// Sphere radius r (finite, >= 0).
        #[arg(long, allow_hyphen_values = true)]
        radius: f64,
        /// Arithmetic precision.
        #[arg(long, value_enum, default_value_t = PrecisionArg::F64)]
        precision: PrecisionArg,
        /// The homework's formula (naive) or the stable rewrite.
        #[arg(long, value_enum, default_value_t = MethodArg::Stable)]
        method: MethodArg,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Write a blank answers file: every question of a variant, every key commented out.
    Template {
        /// Variant seed (0 = the notes' worked example).
        #[arg(long, default_value_t = 0)]
        seed: u64,
    },
    /// Grade an answers file (TOML). Exit status 0 = all correct, 1 = some wrong, 2 = unreadable.
    Check {
        /// The answers file.
        file: PathBuf,
        /// Variant seed (overrides `[meta] seed` in the file).
        #[arg(long)]
        seed: Option<u64>,
        /// Report format.
        #[arg(long, value_enum, default_value_t = FormatArg::Text)]
        format: FormatArg,
    },
    /// Q5: the effect tables (light-path grammar, seed's answers, measured cells).
    EffectsTable {
        /// Print one JSON object instead of markdown tables.
        #[arg(long)]
        json: bool,
    },
    /// Print a randomised variant of a question with its solution.
    Variant {
        /// The question (q2).
        #[arg(long)]
        question: String,
        /// Variant seed (0 = the notes' worked example).
        #[arg(long, default_value_t = 0)]
        seed: u64,
    },
    /// Q4: irradiance E(n) of an environment map through a light probe.
    Irradiance(Q4IrradianceArgs),
    /// Regenerate every figure of the course notes.
    Figures {
        /// Output folder.
        #[arg(long, default_value = "docs/figures")]
        out: PathBuf,
    },
    /// Q3: traverse the homework's 2-D kd-tree with one ray and print the trace.
    KdTrace {
        /// The ray's origin `e`, as `X,Y`.
        #[arg(long, allow_hyphen_values = true)]
        origin: String,
        /// The ray's direction `d`, as `X,Y` (non-zero).
        #[arg(long, allow_hyphen_values = true)]
        dir: String,
        /// Print JSON (`leaves` and `steps`) instead of text.
        #[arg(long)]
        json: bool,
    },
    /// List the built-in scenes of the renderer.
    Scenes,
    /// Print which light-path classes a built-in scene carries and the passes the renderer plans.
    Effects {
        /// A built-in scene (see `hw3 scenes`).
        scene: String,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Render a built-in scene to a PNG (Whitted ray tracing).
    Render {
        /// A built-in scene (see `hw3 scenes`).
        scene: String,
        /// Samples per pixel.
        #[arg(long, default_value_t = 4)]
        spp: u32,
        /// Image size, WIDTHxHEIGHT.
        #[arg(long, default_value = "320x240")]
        size: String,
        /// Output PNG file.
        #[arg(long, default_value = "render.png")]
        out: PathBuf,
        /// `auto` runs the planned passes, `all` every pass.
        #[arg(long, default_value = "auto")]
        effects: String,
    },
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum PrecisionArg {
    F32,
    F64,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum MethodArg {
    Naive,
    Stable,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum FormatArg {
    Text,
    Json,
    Gradescope,
}

#[derive(clap::Args)]
struct Q4IrradianceArgs {
    /// `constant:L`, `sky` (hemisphere step, +z up), `linear:A,B` (L = A + B ω_z), or a lat-long .hdr file.
    #[arg(long)]
    env: String,
    /// Surface normal `X,Y,Z` (any non-zero length).
    #[arg(long, allow_hyphen_values = true)]
    normal: String,
    /// unweighted|weighted|uniform|cosine|map|mis|sh9
    #[arg(long)]
    method: String,
    /// Monte Carlo samples.
    #[arg(long, default_value_t = 256)]
    samples: usize,
    /// Monte Carlo seed.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Texels across the mirror-ball probe analytic maps are rasterised into.
    #[arg(long, default_value_t = 256)]
    size: usize,
    /// Print `{"irradiance":[r,g,b]}`.
    #[arg(long)]
    json: bool,
}

/// An error the user caused: reported on one line, exit status 2, nothing written.
#[derive(Debug)]
struct UsageError(String);

impl std::fmt::Display for UsageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for UsageError {}

/// `hw3 check` found wrong answers: exit status 1, the report already printed.
#[derive(Debug)]
struct SomeWrong;

impl std::fmt::Display for SomeWrong {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("some answers are not correct")
    }
}

impl std::error::Error for SomeWrong {}

/// Lets `hw3 … | head` end quietly: with SIGPIPE at its default, a closed pipe ends the process
/// like any Unix filter, instead of making `println!` panic on a broken pipe.
fn restore_default_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called first thing in main, before any thread exists; it only resets the
    // disposition of one signal to its default.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn main() -> ExitCode {
    restore_default_sigpipe();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.downcast_ref::<SomeWrong>().is_some() => ExitCode::from(1),
        Err(e) if e.downcast_ref::<UsageError>().is_some() => {
            eprintln!("hw3: {e}");
            ExitCode::from(2)
        }
        Err(e) => {
            eprintln!("hw3: {e:#}");
            ExitCode::from(1)
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        None => {
            print_answers(None)?;
            write_figures(&PathBuf::from("docs/figures"))
        }
        Some(Command::Answers { question }) => print_answers(question.as_deref()),
        Some(Command::Figures { out }) => write_figures(&out),
        Some(Command::Template { seed }) => {
            print!("{}", hw3::checker::template(seed).map_err(|e| UsageError(e.to_string()))?);
            Ok(())
        }
        Some(Command::Variant { question, seed }) => {
            let variant = hw3::checker::variant(&question, seed).map_err(|e| UsageError(e.to_string()))?;
            let key = hw3::checker::answers_key_for(&question, seed).map_err(|e| UsageError(e.to_string()))?;
            println!("{}\n\nSolution, as an answers file:\n[meta]\nseed = {seed}\n{key}", variant.statement);
            Ok(())
        }
        Some(Command::Check { file, seed, format }) => {
            let text = std::fs::read_to_string(&file)
                .map_err(|e| UsageError(format!("cannot read {}: {e}", file.display())))?;
            let report = hw3::checker::check(&text, seed)
                .map_err(|e| UsageError(format!("{}: {e}", file.display()).replace('\n', " ")))?;
            match format {
                FormatArg::Text => println!("{}", hw3::checker::report_text(&report)),
                FormatArg::Json => println!("{}", serde_json::to_string_pretty(&report)?),
                FormatArg::Gradescope => {
                    println!("{}", serde_json::to_string_pretty(&hw3::checker::report_gradescope(&report))?)
                }
            }
            if report.all_correct() { Ok(()) } else { Err(SomeWrong.into()) }
        }
        Some(Command::KdTrace { origin, dir, json }) => {
            let out =
                hw3::q3_kd_traversal::kd_trace_command(&origin, &dir, json).map_err(|e| UsageError(e.to_string()))?;
            println!("{out}");
            Ok(())
        }
        Some(Command::Sphere { origin, dir, center, radius, precision, method, json }) => {
            use hw3::q2_ray_sphere::catalogue::{Method, Precision};
            let (ray, sphere) =
                hw3::q2_ray_sphere::parse_sphere_args(&origin, &dir, &center, radius).map_err(UsageError)?;
            let precision = match precision {
                PrecisionArg::F32 => Precision::F32,
                PrecisionArg::F64 => Precision::F64,
            };
            let method = match method {
                MethodArg::Naive => Method::Naive,
                MethodArg::Stable => Method::Stable,
            };
            let answer =
                hw3::q2_ray_sphere::solve(&ray, &sphere, method, precision).map_err(|e| UsageError(e.to_string()))?;
            if json {
                println!("{}", serde_json::to_string(&answer)?);
            } else {
                println!("{answer:#?}");
            }
            Ok(())
        }
        Some(Command::Scenes) => {
            print!("{}", hw3::render::command::scenes_text());
            Ok(())
        }
        Some(Command::Effects { scene, json }) => {
            let text = hw3::render::command::effects_text(&scene, json).map_err(|e| UsageError(e.to_string()))?;
            print!("{text}");
            Ok(())
        }
        Some(Command::Render { scene, spp, size, out, effects }) => render_to_file(&scene, spp, &size, &out, &effects),
        Some(Command::Irradiance(args)) => {
            let normal = hw3::geometry::parse_vec3("--normal", &args.normal).map_err(UsageError)?;
            let request = hw3::q4_light_probe::IrradianceRequest {
                env: args.env,
                normal,
                method: args.method,
                samples: args.samples,
                seed: args.seed,
                size: args.size,
                json: args.json,
            };
            let out = hw3::q4_light_probe::irradiance_command(&request).map_err(|e| UsageError(e.to_string()))?;
            println!("{out}");
            Ok(())
        }
        Some(Command::EffectsTable { json }) => {
            println!("{}", hw3::q5_effect_tables::effects_table_command(json).map_err(anyhow::Error::msg)?);
            Ok(())
        }
    }
}

fn render_to_file(scene: &str, spp: u32, size: &str, out: &PathBuf, effects: &str) -> anyhow::Result<()> {
    use hw3::render::command::{parse_size, render_scene};
    let size = parse_size(size).map_err(UsageError)?;
    let mode = effects.parse().map_err(UsageError)?;
    let output = render_scene(scene, spp, size, mode).map_err(|e| UsageError(e.to_string()))?;
    std::fs::write(out, &output.png).with_context(|| format!("writing {}", out.display()))?;
    eprintln!("{} → {}", output.summary, out.display());
    Ok(())
}

fn print_answers(question: Option<&str>) -> anyhow::Result<()> {
    let all = hw3::all_answers();
    if let Some(q) = question
        && !all.iter().any(|a| a.question == q)
    {
        let known: Vec<_> = all.iter().map(|a| a.question).collect();
        return Err(UsageError(format!("unknown question `{q}`; known: {}", known.join(", "))).into());
    }
    for answers in all.iter().filter(|a| question.is_none_or(|q| a.question == q)) {
        println!("== {} — {} ==\n{}\n", answers.question.to_uppercase(), answers.title, answers.text);
    }
    Ok(())
}

fn write_figures(out: &PathBuf) -> anyhow::Result<()> {
    let figures = hw3::all_figures().context("drawing figures")?;
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    for figure in &figures {
        let path = out.join(&figure.file_name);
        let unchanged = std::fs::read(&path).is_ok_and(|old| old == figure.bytes);
        if !unchanged {
            std::fs::write(&path, &figure.bytes).with_context(|| format!("writing {}", path.display()))?;
        }
    }
    eprintln!("{} figures in {}", figures.len(), out.display());
    Ok(())
}
