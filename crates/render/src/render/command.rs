//! The logic of `hw3 scenes`, `hw3 paths` and `hw3 render`, kept out of `main.rs` so that it can
//! be tested without spawning the binary.

use super::{RenderError, Settings, catalogue, render};
use super::{
    analysis::{Analysis, analyze},
    passes::{Pass, Passes},
};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::fmt::Write as _;
use std::io::IsTerminal as _;
use std::time::Instant;

/// `hw3 scenes`: one line per built-in scene.
///
/// # Examples
/// ```
/// assert!(hw3_render::render::command::scenes_text().contains("mirrors"));
/// ```
#[must_use]
pub fn scenes_text() -> String {
    catalogue::CATALOGUE.iter().map(|(name, description)| format!("{name:16} {description}\n")).collect()
}

/// `hw3 paths SCENE [--json]`: the path classes that carry energy and the pass plan.
///
/// # Errors
/// [`RenderError::UnknownScene`].
///
/// # Examples
/// ```
/// let text = hw3_render::render::command::effects_text("fog", false).unwrap();
/// assert!(text.contains("in_scattering      run"));
/// let json = hw3_render::render::command::effects_text("fog", true).unwrap();
/// assert!(json.contains("\"in_scattering\": true"));
/// ```
pub fn effects_text(scene_name: &str, json: bool) -> Result<String, RenderError> {
    let analysis = analyze(&catalogue::by_name(scene_name)?);
    if json {
        return Ok(serde_json::to_string_pretty(&analysis).expect("plain data serialises") + "\n");
    }
    Ok(describe(scene_name, &analysis))
}

fn describe(scene_name: &str, analysis: &Analysis) -> String {
    let mut text = format!("scene {scene_name}\npath classes (Heckbert, light first):\n");
    for class in &analysis.classes {
        let mark = if class.carries_energy { "yes" } else { "no " };
        let _ = writeln!(text, "  {mark} {:18} {:44} ({})", class.notation, class.effect, class.reason);
    }
    let _ = writeln!(
        text,
        "medium extinction on every segment: {}\nobjects move during the shutter: {}\nplan:",
        yes_no(analysis.extinction),
        yes_no(analysis.moving)
    );
    for pass in Pass::ALL {
        let state = if analysis.plan.get(pass) { "run" } else { "skip" };
        let note = match pass {
            Pass::IndirectBounces => " (path tracer only; hw3 render traces Whitted-style)",
            Pass::Caustics => " (Whitted only: a caustic photon map; the path tracer bounces into lights)",
            _ => "",
        };
        let _ = writeln!(text, "  {:18} {state}{note}", pass.name());
    }
    if !analysis.not_rendered.is_empty() {
        let _ = writeln!(text, "carried but not rendered (no pass for it): {}", analysis.not_rendered.join(", "));
    }
    text
}

fn yes_no(flag: bool) -> &'static str {
    if flag { "yes" } else { "no" }
}

/// `--size` is not two whole numbers joined by `x` ([`parse_size`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("--size: expected WIDTHxHEIGHT like 320x240, got `{text}`")]
pub struct ParseSizeError {
    /// The text given.
    pub text: String,
}

/// Parses `--size WxH` (`64x48`).
///
/// # Errors
/// [`ParseSizeError`] with the text when it is not two whole numbers joined by `x`.
///
/// # Examples
/// ```
/// use hw3_render::render::command::{ParseSizeError, parse_size};
/// assert_eq!(parse_size("64x48"), Ok((64, 48)));
/// assert_eq!(parse_size("64"), Err(ParseSizeError { text: "64".into() }));
/// ```
pub fn parse_size(text: &str) -> Result<(u32, u32), ParseSizeError> {
    let parsed = text.split_once(['x', 'X']).and_then(|(w, h)| Some((w.trim().parse().ok()?, h.trim().parse().ok()?)));
    parsed.ok_or_else(|| ParseSizeError { text: text.to_owned() })
}

/// Which passes `hw3 render` runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EffectsMode {
    /// The analysis' plan.
    Auto,
    /// Every pass (the brute-force render).
    All,
}

/// `--effects` is neither `auto` nor `all` ([`EffectsMode`]'s `FromStr`).
///
/// # Examples
/// ```
/// use hw3_render::render::command::{EffectsMode, ParseEffectsModeError};
/// assert_eq!("all".parse(), Ok(EffectsMode::All));
/// let error = "some".parse::<EffectsMode>().unwrap_err();
/// assert_eq!(error, ParseEffectsModeError { text: "some".into() });
/// assert_eq!(error.to_string(), "--effects: expected auto or all, got `some`");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("--effects: expected auto or all, got `{text}`")]
pub struct ParseEffectsModeError {
    /// The text given.
    pub text: String,
}

impl std::str::FromStr for EffectsMode {
    type Err = ParseEffectsModeError;

    fn from_str(text: &str) -> Result<Self, ParseEffectsModeError> {
        match text {
            "auto" => Ok(Self::Auto),
            "all" => Ok(Self::All),
            _ => Err(ParseEffectsModeError { text: text.to_owned() }),
        }
    }
}

/// A finished `hw3 render`: the PNG bytes and a one-line summary for stderr.
#[derive(Debug, Clone)]
pub struct RenderOutput {
    /// The encoded PNG.
    pub png: Vec<u8>,
    /// Scene, size, spp, passes run and wall time.
    pub summary: String,
}

/// Renders of more camera samples than this show a progress bar (on a terminal): smaller ones
/// finish before a bar would be worth drawing.
pub const PROGRESS_MIN_SAMPLES: u64 = 1 << 18;

/// `hw3 render`: renders a built-in scene with Whitted tracing. Draws a progress bar on stderr
/// when stderr is a terminal and the render is long ([`PROGRESS_MIN_SAMPLES`]); writes nothing
/// to stderr otherwise (a pipe or a file gets only the summary `main` prints).
///
/// # Errors
/// [`RenderError`] for an unknown scene or an out-of-range size or sample count (checked before
/// any work is done).
///
/// # Examples
/// ```
/// use hw3_render::render::command::{render_scene, EffectsMode};
/// let out = render_scene("still", 1, (8, 6), EffectsMode::Auto).unwrap();
/// assert!(out.summary.starts_with("still: 8x6 at 1 spp"));
/// ```
pub fn render_scene(
    scene_name: &str,
    spp: u32,
    size: (u32, u32),
    mode: EffectsMode,
) -> Result<RenderOutput, RenderError> {
    let target =
        if std::io::stderr().is_terminal() { ProgressDrawTarget::stderr() } else { ProgressDrawTarget::hidden() };
    render_scene_to(scene_name, spp, size, mode, target)
}

/// [`render_scene`] drawing its progress bar (rows done, elapsed time, estimated time left) to
/// `target` instead of stderr. The bar is drawn only for renders of more than
/// [`PROGRESS_MIN_SAMPLES`] camera samples, and cleared when the render ends.
///
/// # Errors
/// As [`render_scene`]; nothing is drawn when an error is returned.
pub fn render_scene_to(
    scene_name: &str,
    spp: u32,
    size: (u32, u32),
    mode: EffectsMode,
    target: ProgressDrawTarget,
) -> Result<RenderOutput, RenderError> {
    let scene = catalogue::by_name(scene_name)?;
    let mut settings = Settings::whitted(size.0, size.1, spp, Passes::all());
    if mode == EffectsMode::Auto {
        settings.passes = settings.integrator.restrict(analyze(&scene).plan);
    }
    let passes = settings.passes;
    super::check_settings(&settings)?;
    let samples = u64::from(size.0) * u64::from(size.1) * u64::from(spp);
    let target = if samples > PROGRESS_MIN_SAMPLES { target } else { ProgressDrawTarget::hidden() };
    let bar = ProgressBar::with_draw_target(Some(u64::from(size.1)), target).with_style(
        ProgressStyle::with_template("rendering {bar:40} {pos}/{len} rows, {elapsed} elapsed, ~{eta} left")
            .expect("a fixed, valid template"),
    );
    let start = Instant::now();
    let image = render(&scene, &settings, &|rows| bar.set_position(u64::from(rows)))?;
    let seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let run: Vec<&str> = Pass::ALL.iter().filter(|&&p| passes.get(p)).map(|p| p.name()).collect();
    let png = hw3_core::plot::png_bytes("render.png", &image.to_rgb8())
        .expect("encoding an in-memory RGB image cannot fail")
        .bytes;
    Ok(RenderOutput {
        png,
        summary: format!(
            "{scene_name}: {}x{} at {spp} spp, passes [{}], {seconds:.3} s",
            size.0,
            size.1,
            run.join(", ")
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn effects_text_shows_classes_and_plan() {
        let text = effects_text("mirrors", false).unwrap();
        assert!(text.contains("yes L(D|G)?S+E"));
        assert!(text.contains("specular_recursion run"));
        assert!(text.contains("time_sampling      skip"));
        assert!(text.contains("caustics           run (Whitted only"), "the point light's caustics get photons");
        assert!(!text.contains("carried but not rendered"));
        assert!(effects_text("caustic", true).unwrap().contains("\"caustics\": true"));
        assert!(effects_text("diffuse-spheres", true).unwrap().contains("\"caustics\": false"));
        assert!(matches!(effects_text("nope", true), Err(RenderError::UnknownScene { .. })));
    }

    /// The analysis of every built-in scene, as `hw3 paths` prints it.
    #[test]
    fn effects_of_every_built_in_scene() {
        let text: String =
            catalogue::CATALOGUE.iter().map(|(name, _)| effects_text(name, false).unwrap() + "\n").collect();
        crate::testing::insta_settings().bind(|| insta::assert_snapshot!("render_effects_of_built_in_scenes", text));
    }

    #[test]
    fn render_scene_refuses_bad_input_before_working() {
        assert!(matches!(render_scene("still", 1, (0, 4), EffectsMode::Auto), Err(RenderError::ImageSize { .. })));
        assert!(matches!(render_scene("still", 0, (4, 4), EffectsMode::Auto), Err(RenderError::SamplesPerPixel(0))));
        let out = render_scene("still", 1, (8, 6), EffectsMode::All).unwrap();
        assert!(out.png.starts_with(b"\x89PNG"));
        assert!(out.summary.contains("time_sampling"));
    }

    /// A terminal stand-in that records what indicatif draws.
    #[derive(Debug, Clone, Default)]
    struct RecordingTerminal(std::sync::Arc<std::sync::Mutex<String>>);

    impl RecordingTerminal {
        fn record(&self, text: &str) -> std::io::Result<()> {
            self.0.lock().expect("no test thread panicked while drawing").push_str(text);
            Ok(())
        }
    }

    impl indicatif::TermLike for RecordingTerminal {
        fn width(&self) -> u16 {
            100
        }
        fn move_cursor_up(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_down(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_right(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_left(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn write_line(&self, text: &str) -> std::io::Result<()> {
            self.record(&format!("{text}\n"))
        }
        fn write_str(&self, text: &str) -> std::io::Result<()> {
            self.record(text)
        }
        fn clear_line(&self) -> std::io::Result<()> {
            self.record("<clear>")
        }
        fn flush(&self) -> std::io::Result<()> {
            Ok(())
        }
    }

    /// On a terminal a long render draws the bar (with its row count); a short one draws nothing.
    #[test]
    fn long_renders_draw_a_progress_bar_on_a_terminal_and_short_ones_do_not() {
        let draw = |size: (u32, u32)| {
            let terminal = RecordingTerminal::default();
            let target = ProgressDrawTarget::term_like(Box::new(terminal.clone()));
            render_scene_to("still", 1, size, EffectsMode::Auto, target).unwrap();
            terminal.0.lock().unwrap().clone()
        };
        let long = (520, 510);
        assert!(u64::from(long.0 * long.1) > PROGRESS_MIN_SAMPLES);
        let drawn = draw(long);
        assert!(drawn.contains("rendering") && drawn.contains("/510 rows"), "{drawn}");
        assert_eq!(draw((64, 48)), "");
    }

    #[test]
    fn sizes_and_modes_parse_or_explain() {
        assert_eq!(parse_size("8X6"), Ok((8, 6)));
        assert!(parse_size("8x").is_err());
        assert!(parse_size("-1x5").is_err());
        assert_eq!("all".parse::<EffectsMode>(), Ok(EffectsMode::All));
        assert!("some".parse::<EffectsMode>().is_err());
    }
}
