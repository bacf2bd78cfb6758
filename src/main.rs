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
    /// Regenerate every figure of the course notes.
    Figures {
        /// Output folder.
        #[arg(long, default_value = "docs/figures")]
        out: PathBuf,
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
        Some(Command::Scenes) => {
            print!("{}", hw3::render::command::scenes_text());
            Ok(())
        }
        Some(Command::Effects { scene, json }) => {
            let text = hw3::render::command::effects_text(&scene, json)
                .map_err(|e| UsageError(e.to_string()))?;
            print!("{text}");
            Ok(())
        }
        Some(Command::Render {
            scene,
            spp,
            size,
            out,
            effects,
        }) => render_to_file(&scene, spp, &size, &out, &effects),
    }
}

fn render_to_file(
    scene: &str,
    spp: u32,
    size: &str,
    out: &PathBuf,
    effects: &str,
) -> anyhow::Result<()> {
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
