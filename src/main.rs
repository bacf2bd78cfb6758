//! `hw3`: prints every answer and regenerates every figure; subcommands compute single answers.
//!
//! Exit status: 0 on success, 1 when `check` finds wrong answers (or on an internal failure),
//! 2 on invalid input (one line on stderr, nothing written), 3 when the output cannot be written
//! (a full disk, a closed stdout): the README's table "Exit statuses and limits".

use clap::{Parser, Subcommand};
use hw3::cli::{self as limits, one_line};
use hw3::fsio::io_reason;
use std::io::Write as _;
use std::path::{Path, PathBuf};
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
        /// Sphere radius r (finite, > 0).
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
        /// Variant seed, 0 … 2^63 − 1 (0 = the homework's own numbers where it has them).
        #[arg(long, default_value_t = 0, value_parser = seed_arg, allow_hyphen_values = true)]
        seed: u64,
    },
    /// Grade answers files (TOML): one, or a class at once. Exit status 0 = all correct, 1 = some wrong, 2 = unreadable.
    ///
    /// One file: its report; an unreadable file is exit status 2. Several files or a folder (its
    /// *.toml files, sorted): one class report with per-part statistics; a file that cannot be
    /// graded is a row of the report (exit status 1), and exit status 2 means no file could be.
    Check {
        /// The answers file; for a class, several files or folders.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Variant seed, 0 … 2^63 − 1 (overrides `[meta] seed` in the file).
        #[arg(long, value_parser = seed_arg, allow_hyphen_values = true)]
        seed: Option<u64>,
        /// Report format.
        #[arg(long, value_enum, default_value_t = FormatArg::Text)]
        format: FormatArg,
        /// Write the report to this file instead of stdout (replaced atomically); for a class
        /// with --format gradescope, a folder that receives one results file per student.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Q5: the effect tables (light-path grammar, the student's answers, measured cells).
    #[command(alias = "effects-table")]
    EffectTables {
        /// Print one JSON object instead of markdown tables.
        #[arg(long)]
        json: bool,
    },
    /// Print a randomised variant of a question with its solution.
    Variant {
        /// The question (q2).
        #[arg(long)]
        question: String,
        /// Variant seed, 0 … 2^63 − 1 (0 = the homework's own numbers where it has them).
        #[arg(long, default_value_t = 0, value_parser = seed_arg, allow_hyphen_values = true)]
        seed: u64,
    },
    /// Print the step-by-step solution of a variant: every intermediate number, then the answers.
    Solution {
        /// Variant seed, 0 … 2^63 − 1 (0 = the homework's own numbers).
        #[arg(long, default_value_t = 0, value_parser = seed_arg, allow_hyphen_values = true)]
        seed: u64,
        /// Only this question (q1 … q5).
        #[arg(long)]
        question: Option<String>,
        /// `text` for a terminal, `markdown` for a hand-out.
        #[arg(long, default_value = "text", value_parser = ["text", "markdown"])]
        format: String,
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
    #[command(alias = "effects")]
    Paths {
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
        /// Samples per pixel (1 … 65536; width × height × spp at most 2^22 without --allow-large).
        #[arg(long, default_value_t = 4, value_parser = spp_arg, allow_hyphen_values = true)]
        spp: u32,
        /// Image size, WIDTHxHEIGHT (each side 1 … 8192).
        #[arg(long, default_value = "320x240", allow_hyphen_values = true)]
        size: String,
        /// Output PNG file (its name must end in .png; its folder must exist).
        #[arg(long, default_value = "render.png")]
        out: PathBuf,
        /// `auto` runs the planned passes, `all` every pass.
        #[arg(long, default_value = "auto")]
        effects: String,
        /// Allow up to 2^40 camera samples (days of work) instead of 2^22.
        #[arg(long)]
        allow_large: bool,
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
    Csv,
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
    #[arg(long, value_parser = method_arg)]
    method: String,
    /// Monte Carlo samples (1 … 2^20; 2^30 with --allow-large).
    #[arg(long, default_value_t = 256, value_parser = count_arg, allow_hyphen_values = true)]
    samples: u64,
    /// Monte Carlo seed.
    #[arg(long, default_value_t = 0, value_parser = count_arg, allow_hyphen_values = true)]
    seed: u64,
    /// Texels across the mirror-ball probe analytic maps are rasterised into (16 … 1024; 4096
    /// with --allow-large).
    #[arg(long, default_value_t = 256, value_parser = count_arg, allow_hyphen_values = true)]
    size: u64,
    /// Print `{"irradiance":[r,g,b]}`.
    #[arg(long)]
    json: bool,
    /// Raise the bounds on --samples, --size and the map's texels (see their help).
    #[arg(long)]
    allow_large: bool,
}

/// `--seed` of `template`, `check` and `variant`.
fn seed_arg(text: &str) -> Result<u64, String> {
    limits::parse_seed(text).map_err(|e| e.to_string())
}

/// A count whose bound is checked later, with `--allow-large` known.
fn count_arg(text: &str) -> Result<u64, String> {
    limits::parse_unsigned(text, u64::MAX).map_err(|e| e.to_string())
}

/// `render --spp`: the renderer's own range.
fn spp_arg(text: &str) -> Result<u32, String> {
    let spp = limits::parse_unsigned(text, u64::from(hw3::render::MAX_SPP)).map_err(|e| e.to_string())?;
    if spp == 0 { Err("expected at least 1 sample per pixel, got `0`".into()) } else { Ok(spp as u32) }
}

/// `irradiance --method`, checked by the parser so that the message names `--method`.
fn method_arg(text: &str) -> Result<String, String> {
    text.parse::<hw3::q4_light_probe::irradiance::Estimator>().map(|_| text.to_owned())
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

/// The output could not be written (stdout, or a file after the work): exit status 3.
#[derive(Debug)]
struct OutputError(String);

impl std::fmt::Display for OutputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for OutputError {}

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

/// One line on stderr, cleaned ([`one_line`]); a stderr that cannot be written is ignored, since
/// there is nowhere left to report it.
fn report(message: &str) {
    let _ = writeln!(std::io::stderr(), "{}", one_line(&format!("hw3: {message}")));
}

/// Writes `text` to stdout, turning a write failure (a full disk, a closed descriptor) into exit
/// status 3 instead of a panic.
fn emit(text: &str) -> anyhow::Result<()> {
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
        .map_err(|e| OutputError(format!("cannot write to stdout: {}", io_reason(&e))).into())
}

/// [`emit`] with a line break.
fn emit_line(text: &str) -> anyhow::Result<()> {
    emit(&format!("{text}\n"))
}

/// Deletes the temporaries of unfinished writes when the process is interrupted (`SIGINT`,
/// `SIGTERM`, `SIGHUP`), then dies of the same signal, so that the shell sees an interrupt as
/// one. The signals are blocked in every thread and taken by one thread that waits for them: the
/// cleanup then runs as ordinary code, not inside a signal handler.
fn remove_temporaries_on_interrupt() {
    #[cfg(unix)]
    // SAFETY: called in main before any other thread exists, so that every thread inherits the
    // mask; the set is initialised by sigemptyset before use, and the waiting thread only calls
    // sigwait, the file removal, and the async-signal-safe signal, pthread_sigmask and raise.
    unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&raw mut set);
        for signal in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
            libc::sigaddset(&raw mut set, signal);
        }
        libc::pthread_sigmask(libc::SIG_BLOCK, &raw const set, std::ptr::null_mut());
        std::thread::spawn(move || {
            let mut signal = 0;
            if libc::sigwait(&raw const set, &raw mut signal) != 0 {
                return;
            }
            hw3::fsio::remove_temporaries();
            libc::signal(signal, libc::SIG_DFL);
            libc::pthread_sigmask(libc::SIG_UNBLOCK, &raw const set, std::ptr::null_mut());
            libc::raise(signal);
        });
    }
}

/// Whether standard output is open. Rust's runtime, before `main`, puts `/dev/null` (opened for
/// reading and writing) on a standard descriptor it finds closed, so that `hw3 … >&-` would
/// otherwise end with status 0 and its output lost. That is what is recognised here: descriptor 1
/// missing, or being `/dev/null` open for reading and writing (a shell's `> /dev/null` opens it
/// for writing only, and stays allowed).
fn stdout_is_open() -> bool {
    #[cfg(unix)]
    // SAFETY: fcntl(F_GETFL) and fstat read the state of descriptor 1 and change nothing; `stat`
    // is a plain struct that fstat fills.
    unsafe {
        let flags = libc::fcntl(1, libc::F_GETFL);
        if flags == -1 {
            return false;
        }
        let mut own: libc::stat = std::mem::zeroed();
        if libc::fstat(1, &raw mut own) != 0 {
            return false;
        }
        let null = std::fs::metadata("/dev/null");
        #[allow(clippy::useless_conversion, reason = "dev_t is u64 on Linux, narrower on other Unixes")]
        let device = u64::from(own.st_rdev);
        let is_null = null.is_ok_and(|n| {
            use std::os::unix::fs::MetadataExt as _;
            (own.st_mode & libc::S_IFMT) == libc::S_IFCHR && device == n.rdev()
        });
        !(is_null && flags & libc::O_ACCMODE == libc::O_RDWR)
    }
    #[cfg(not(unix))]
    true
}

/// Whether a command prints its result on stdout (the others write files, and say so on stderr).
fn writes_stdout(command: Option<&Command>) -> bool {
    match command {
        Some(Command::Render { .. } | Command::Figures { .. }) => false,
        Some(Command::Check { out, .. }) => out.is_none(),
        _ => true,
    }
}

/// clap's error on one line, with the value it quotes in backticks, so that [`one_line`] cuts a long
/// value and keeps the reason after it.
fn clap_message(first_line: &str) -> String {
    let message = first_line.strip_prefix("error: ").unwrap_or(first_line);
    if let Some(rest) = message.strip_prefix("invalid value '")
        && let Some((value, reason)) = rest.rsplit_once("' for '")
    {
        return format!("invalid value `{value}` for '{reason}");
    }
    message.to_owned()
}

fn main() -> ExitCode {
    restore_default_sigpipe();
    remove_temporaries_on_interrupt();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // --help and --version: their text is the output.
            if !stdout_is_open() {
                report("stdout is closed: nothing done, since the result would be lost");
                return ExitCode::from(3);
            }
            let text = e.render().to_string();
            return match emit(&text) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    report(&e.to_string());
                    ExitCode::from(3)
                }
            };
        }
        Err(e) => {
            // clap's first line is the error; its usage block and tips are dropped, to keep the
            // promise of one line.
            // Its first paragraph: the error, and the arguments it lists on the lines after a colon.
            let rendered = e.render().to_string();
            let first: Vec<&str> = rendered.lines().take_while(|l| !l.trim().is_empty()).map(str::trim).collect();
            let first = if first.is_empty() { "invalid arguments".to_owned() } else { first.join(" ") };
            report(&format!("{} (see --help)", clap_message(&first)));
            return ExitCode::from(2);
        }
    };
    if writes_stdout(cli.command.as_ref()) && !stdout_is_open() {
        report("stdout is closed: nothing done, since the result would be lost");
        return ExitCode::from(3);
    }
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.downcast_ref::<SomeWrong>().is_some() => ExitCode::from(1),
        Err(e) if e.downcast_ref::<UsageError>().is_some() => {
            report(&e.to_string());
            ExitCode::from(2)
        }
        Err(e) if e.downcast_ref::<OutputError>().is_some() => {
            report(&e.to_string());
            ExitCode::from(3)
        }
        Err(e) => {
            report(&format!("{e:#}"));
            ExitCode::from(1)
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        None => {
            let out = PathBuf::from("docs/figures");
            check_out_folder(&out)?;
            print_answers(None)?;
            write_figures(&out)
        }
        Some(Command::Answers { question }) => print_answers(question.as_deref()),
        Some(Command::Figures { out }) => {
            check_out_folder(&out)?;
            write_figures(&out)
        }
        Some(Command::Template { seed }) => emit(&hw3::checker::template(seed).map_err(|e| UsageError(e.to_string()))?),
        Some(Command::Variant { question, seed }) => {
            let variant = hw3::checker::variant(&question, seed).map_err(|e| UsageError(e.to_string()))?;
            let key = hw3::checker::answer_key_for(&question, seed).map_err(|e| UsageError(e.to_string()))?;
            emit_line(&format!("{}\n\nSolution, as an answers file:\n[meta]\nseed = {seed}\n{key}", variant.statement))
        }
        Some(Command::Solution { seed, question, format }) => {
            // Every error of a solution is a question or a format the user typed.
            let usage = |e: hw3::solution::SolutionError| anyhow::Error::from(UsageError(e.to_string()));
            let format = format.parse().map_err(usage)?;
            emit_line(&hw3::solution::command(question.as_deref(), seed, format).map_err(usage)?)
        }
        Some(Command::Check { files, seed, format, out }) => check(&files, seed, format, out.as_deref()),
        Some(Command::KdTrace { origin, dir, json }) => {
            let out =
                hw3::q3_kd_traversal::kd_trace_command(&origin, &dir, json).map_err(|e| UsageError(e.to_string()))?;
            emit_line(&out)
        }
        Some(Command::Sphere { origin, dir, center, radius, precision, method, json }) => {
            use hw3::q2_ray_sphere::catalogue::{Precision, Solver};
            let (ray, sphere) = hw3::q2_ray_sphere::parse_sphere_args(&origin, &dir, &center, radius)
                .map_err(|e| UsageError(e.to_string()))?;
            let precision = match precision {
                PrecisionArg::F32 => Precision::F32,
                PrecisionArg::F64 => Precision::F64,
            };
            let method = match method {
                MethodArg::Naive => Solver::Naive,
                MethodArg::Stable => Solver::Stable,
            };
            let answer =
                hw3::q2_ray_sphere::solve(&ray, &sphere, method, precision).map_err(|e| UsageError(e.to_string()))?;
            if json { emit_line(&serde_json::to_string(&answer)?) } else { emit_line(&answer.text()) }
        }
        Some(Command::Scenes) => emit(&hw3::render::command::scenes_text()),
        Some(Command::Paths { scene, json }) => {
            emit(&hw3::render::command::effects_text(&scene, json).map_err(|e| UsageError(e.to_string()))?)
        }
        Some(Command::Render { scene, spp, size, out, effects, allow_large }) => {
            render_to_file(&scene, spp, &size, &out, &effects, allow_large)
        }
        Some(Command::Irradiance(args)) => irradiance(args),
        Some(Command::EffectTables { json }) => {
            use hw3::q5_effect_tables::{
                Budget, effect_tables_command, experiments, grammar_table_markdown, measured_tables_markdown,
            };
            // The grammar's tables need no measurement: printed first, they show while the cells
            // are measured (seconds), and an output that cannot take them (a full device, a reader
            // already gone) ends the command before the measuring. If the measuring then fails,
            // they stay printed above the error.
            if !json {
                emit(&grammar_table_markdown()?)?;
            }
            // The message alone: an ExperimentError keeps its source, which `main`'s `{e:#}`
            // would print a second time after it.
            let measured = experiments::measured_table(&Budget::PUBLISHED).map_err(|e| anyhow::anyhow!("{e}"))?;
            if json {
                emit_line(&effect_tables_command(true, &measured).map_err(anyhow::Error::msg)?)
            } else {
                emit_line(&measured_tables_markdown(&measured).map_err(anyhow::Error::msg)?)
            }
        }
    }
}

/// `hw3 check`: one file keeps the single-file contract (an unreadable file is exit status 2);
/// several files or a folder are a class, graded into one report.
fn check(files: &[PathBuf], seed: Option<u64>, format: FormatArg, out: Option<&Path>) -> anyhow::Result<()> {
    use hw3::checker::{check_class, class_csv, class_gradescope, class_text, report_gradescope, report_text};
    let class = files.len() > 1 || files.iter().any(|f| f.is_dir());
    let per_student = class && matches!(format, FormatArg::Gradescope);
    if let Some(out) = out {
        check_report_out(out, per_student, files)?;
    }
    if !class {
        let file = &files[0];
        let text =
            limits::read_text_bounded(file, limits::ANSWERS_FILE_BYTES).map_err(|e| UsageError(e.to_string()))?;
        let name = file.display().to_string();
        let report =
            hw3::checker::check(&text, seed).map_err(|e| UsageError(format!("{}: {e}", limits::quote(&name))))?;
        let body = match format {
            // A student's file may hold terminal escapes: the text report shows them escaped.
            FormatArg::Text => limits::terminal_text(&report_text(&report)),
            FormatArg::Json => limits::json_text(&report)?,
            FormatArg::Csv => class_csv(&check_class(&[(name, Ok(text))], seed)),
            FormatArg::Gradescope => limits::json_text(&report_gradescope(&report))?,
        };
        deliver(out, &body)?;
        return if report.all_correct() { Ok(()) } else { Err(SomeWrong.into()) };
    }
    let paths = hw3::checker::class_files(files).map_err(|e| UsageError(e.to_string()))?;
    let graded = check_class(&hw3::checker::read_class(&paths), seed);
    if graded.graded == 0 {
        let first = &graded.submissions[0];
        return Err(UsageError(format!(
            "no file could be graded ({} files); `{}`: {}",
            graded.submissions.len(),
            limits::quote(&first.file),
            first.error.as_deref().unwrap_or_default()
        ))
        .into());
    }
    match (format, out) {
        (FormatArg::Gradescope, Some(folder)) => {
            let results = hw3::checker::gradescope_files(&graded).map_err(|e| UsageError(e.to_string()))?;
            // Created only now that there are files to put in it.
            std::fs::create_dir_all(folder).map_err(|e| {
                OutputError(format!(
                    "--out: cannot create `{}`: {}",
                    limits::quote(&folder.display().to_string()),
                    io_reason(&e)
                ))
            })?;
            for (name, json) in &results {
                let path = folder.join(name);
                hw3::fsio::write_atomic(&path, format!("{}\n", limits::json_text(json)?).as_bytes())
                    .map_err(|e| OutputError(format!("writing {}: {}", path.display(), io_reason(&e))))?;
            }
            notice(&format!("{} results files in `{}`", results.len(), folder.display()));
        }
        _ => {
            let body = match format {
                FormatArg::Text => limits::terminal_text(&class_text(&graded)),
                FormatArg::Json => limits::json_text(&graded)?,
                FormatArg::Csv => class_csv(&graded),
                FormatArg::Gradescope => limits::json_text(&class_gradescope(&graded))?,
            };
            deliver(out, &body)?;
        }
    }
    if graded.all_correct() { Ok(()) } else { Err(SomeWrong.into()) }
}

/// Checks `check --out` before any grading: a file that can be written ([`check_out_file`]) and
/// is none of the answers files, or, for one results file per student, a folder that exists and
/// accepts files or can be made in one that does (made only once there is something to write).
fn check_report_out(out: &Path, folder: bool, inputs: &[PathBuf]) -> Result<(), UsageError> {
    let shown = || limits::quote(&out.display().to_string());
    if folder {
        return check_out_folder(out);
    }
    check_out_file(out)?;
    if let Some(input) = inputs.iter().find(|input| hw3::fsio::same_file(input, out)) {
        return Err(UsageError(format!(
            "--out: `{}` is the answers file `{}`: the report would replace it",
            shown(),
            limits::quote(&input.display().to_string())
        )));
    }
    Ok(())
}

/// Checks an `--out` file before any work ([`hw3::fsio::check_output_file`]): a name the file
/// system accepts, in a folder that accepts files, and nothing there that is not a regular file.
fn check_out_file(out: &Path) -> Result<(), UsageError> {
    hw3::fsio::check_output_file(out)
        .map_err(|e| UsageError(format!("--out: `{}`: {e}", limits::quote(&out.display().to_string()))))
}

/// A success summary on stderr, on one line with its input escaped ([`one_line`]).
fn notice(message: &str) {
    let _ = writeln!(std::io::stderr(), "{}", one_line(message));
}

/// The report to `out` (replaced atomically), or to stdout.
fn deliver(out: Option<&Path>, body: &str) -> anyhow::Result<()> {
    match out {
        Some(path) => hw3::fsio::write_atomic(path, format!("{body}\n").as_bytes())
            .map_err(|e| OutputError(format!("writing {}: {}", path.display(), io_reason(&e))).into()),
        None => emit_line(body),
    }
}

/// `hw3 irradiance`: every bound is checked, and a map file's header read, before a texel is made.
fn irradiance(args: Q4IrradianceArgs) -> anyhow::Result<()> {
    let large = args.allow_large;
    let usage = |e: limits::LimitError| UsageError(e.to_string());
    let samples = limits::IRRADIANCE_SAMPLES.check("--samples", args.samples, large).map_err(usage)?;
    let size = limits::PROBE_SIZE.check("--size", args.size, large).map_err(usage)?;
    let analytic = args.env == "sky" || args.env.starts_with("constant:") || args.env.starts_with("linear:");
    if !analytic {
        limits::check_hdr_file(Path::new(&args.env), large).map_err(|e| UsageError(e.to_string()))?;
    }
    let normal = hw3::geometry::parse_vec3("--normal", &args.normal).map_err(|e| UsageError(e.to_string()))?;
    let request = hw3::q4_light_probe::IrradianceRequest {
        env: args.env,
        normal,
        method: args.method,
        // Both fit: the limits are far below 2^32.
        samples: usize::try_from(samples).map_err(|e| UsageError(e.to_string()))?,
        seed: args.seed,
        size: usize::try_from(size).map_err(|e| UsageError(e.to_string()))?,
        json: args.json,
    };
    let out = hw3::q4_light_probe::irradiance_command(&request).map_err(|e| UsageError(e.to_string()))?;
    emit_line(&out)
}

/// Checks `--out` of `hw3 render` before any work: a `.png` name, in a folder that exists and
/// accepts files, and not a folder itself.
fn check_render_out(out: &Path) -> Result<(), UsageError> {
    let shown = || limits::quote(&out.display().to_string());
    let is_png = out.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(UsageError(format!("--out: `{}` must end in .png (the renderer writes PNG only)", shown())));
    }
    check_out_file(out)
}

fn render_to_file(
    scene: &str,
    spp: u32,
    size: &str,
    out: &Path,
    effects: &str,
    allow_large: bool,
) -> anyhow::Result<()> {
    use hw3::render::command::render_scene;
    let size = limits::parse_size(size, hw3::render::MAX_SIDE).map_err(|e| UsageError(e.to_string()))?;
    let samples = u64::from(size.0) * u64::from(size.1) * u64::from(spp);
    limits::RENDER_SAMPLES
        .check("camera samples (width × height × --spp)", samples, allow_large)
        .map_err(|e| UsageError(e.to_string()))?;
    let mode = effects.parse::<hw3::render::command::EffectsMode>().map_err(|e| UsageError(e.to_string()))?;
    check_render_out(out)?;
    let output = render_scene(scene, spp, size, mode).map_err(|e| UsageError(e.to_string()))?;
    hw3::fsio::write_atomic(out, &output.png)
        .map_err(|e| OutputError(format!("writing {}: {}", out.display(), io_reason(&e))))?;
    notice(&format!("{} → `{}`", output.summary, out.display()));
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
        emit(&format!("== {} — {} ==\n{}\n\n", answers.question.to_uppercase(), answers.title, answers.text))?;
    }
    Ok(())
}

/// Checks an output folder before any work (the figures, a class's results files): a folder
/// that accepts files, or a path whose nearest existing folder does, so that the missing ones can
/// be made. They are made only when there is something to write ([`make_out_folder`]).
fn check_out_folder(out: &Path) -> Result<(), UsageError> {
    let shown = || limits::quote(&out.display().to_string());
    if out.is_dir() {
        return hw3::fsio::check_writable_dir(out).map_err(|e| UsageError(format!("--out: {e}")));
    }
    if out.exists() {
        return Err(UsageError(format!("--out: `{}` is a file, not a folder", shown())));
    }
    let mut existing = hw3::fsio::parent_dir(out);
    while !existing.exists() {
        existing = hw3::fsio::parent_dir(existing);
    }
    hw3::fsio::check_writable_dir(existing).map_err(|e| UsageError(format!("--out: `{}` cannot be made: {e}", shown())))
}

/// Makes the output folder checked by [`check_out_folder`], once there is something to put in it.
fn make_out_folder(out: &Path) -> Result<(), OutputError> {
    std::fs::create_dir_all(out).map_err(|e| {
        OutputError(format!("--out: cannot create `{}`: {}", limits::quote(&out.display().to_string()), io_reason(&e)))
    })
}

fn write_figures(out: &Path) -> anyhow::Result<()> {
    let figures = hw3::all_figures().map_err(|e| anyhow::anyhow!("drawing figures: {e:#}"))?;
    make_out_folder(out)?;
    for figure in &figures {
        let path = out.join(&figure.file_name);
        let unchanged = std::fs::read(&path).is_ok_and(|old| old == figure.bytes);
        if !unchanged {
            let written = std::fs::create_dir_all(hw3::fsio::parent_dir(&path))
                .and_then(|()| hw3::fsio::write_atomic(&path, &figure.bytes));
            written.map_err(|e| OutputError(format!("writing {}: {}", path.display(), io_reason(&e))))?;
        }
    }
    notice(&format!("{} figures in `{}`", figures.len(), out.display()));
    Ok(())
}
