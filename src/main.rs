//! `hw3`: prints every answer and regenerates every figure; subcommands compute single answers.
//!
//! Exit status: 0 on success, 2 on invalid input (one line on stderr, nothing written),
//! 1 on an internal failure (for example a figure that cannot be written).

use anyhow::Context as _;
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "hw3",
    version,
    about = "Ray-tracing homework 3: answers, figures and checks"
)]
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
    /// Q4: irradiance E(n) of an environment map through a light probe.
    Irradiance(Q4IrradianceArgs),
    /// Regenerate every figure of the course notes.
    Figures {
        /// Output folder.
        #[arg(long, default_value = "docs/figures")]
        out: PathBuf,
    },
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

fn main() -> ExitCode {
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
            let out = hw3::q4_light_probe::irradiance_command(&request)
                .map_err(|e| UsageError(e.to_string()))?;
            println!("{out}");
            Ok(())
        }
    }
}

fn print_answers(question: Option<&str>) -> anyhow::Result<()> {
    let all = hw3::all_answers();
    if let Some(q) = question {
        if !all.iter().any(|a| a.question == q) {
            let known: Vec<_> = all.iter().map(|a| a.question).collect();
            return Err(UsageError(format!(
                "unknown question `{q}`; known: {}",
                known.join(", ")
            ))
            .into());
        }
    }
    for answers in all
        .iter()
        .filter(|a| question.is_none_or(|q| a.question == q))
    {
        println!(
            "== {} — {} ==\n{}\n",
            answers.question.to_uppercase(),
            answers.title,
            answers.text
        );
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
            std::fs::write(&path, &figure.bytes)
                .with_context(|| format!("writing {}", path.display()))?;
        }
    }
    eprintln!("{} figures in {}", figures.len(), out.display());
    Ok(())
}
