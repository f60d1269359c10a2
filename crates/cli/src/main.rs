//! `rslam`: arguments in, library calls out. Each subcommand lives in its own file under
//! `commands/`; exit code 0 = ok, 1 = a check failed, 2 = an error.

mod commands;
mod flags;
mod interrupt;
mod progress_bar;
mod suite_progress;

/// Frames are megabyte buffers made and dropped on several threads; glibc returns them to the
/// kernel and faults them back in on every frame, mimalloc keeps reusing them.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use std::process::ExitCode;

use clap::{CommandFactory, Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "rslam",
    version,
    about = "Robustness benchmarks for RGB-D SLAM: render, perturb, evaluate",
    arg_required_else_help = true
)]
struct Cli {
    /// Print this command-line reference as Markdown (the book's docs/src/reference/cli.md).
    #[arg(long, hide = true)]
    markdown_help: bool,
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Render an RGB-D sequence of a scene along a trajectory, optionally perturbed.
    Render(commands::render::RenderArgs),
    /// Apply perturbations to an existing dataset, image folder or image.
    Perturb(commands::perturb::PerturbArgs),
    /// List every perturbation with its parameters at each severity.
    List(commands::list::ListArgs),
    /// Built-in scenes: export the ground-truth mesh or the default trajectory.
    Scene(commands::scene::SceneArgs),
    /// Evaluate an estimated trajectory against ground truth (ATE, RPE, SR), or many runs;
    /// `eval recon`: a reconstructed map against the ground-truth mesh.
    Eval(commands::eval::EvalArgs),
    /// Check a generated dataset against its checksums (rslam.b3sum) and manifest digest.
    Verify(commands::verify::VerifyArgs),
    /// The benchmark matrix: make, shard, watch and schedule a suite of datasets.
    Suite(commands::suite::SuiteArgs),
    /// Open a window on a scene or dataset: tune perturbations live, scrub, compare trajectories.
    View(commands::view::ViewArgs),
}

/// Mesa's Vulkan drivers probe for a Wayland display and print an "error:" line when
/// XDG_RUNTIME_DIR is unset (headless machines, CI); give the probe a directory to look in.
/// Runs first in `main`, while the process has one thread.
fn quiet_headless_wayland_probe() {
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        std::env::set_var("XDG_RUNTIME_DIR", std::env::temp_dir());
    }
}

fn main() -> ExitCode {
    // `rslam eval ... | head` closes the pipe early: end quietly as `cat` does, not with a
    // panic from `println!`. The workspace forbids unsafe code; the crate holds the one call.
    sigpipe::reset();
    quiet_headless_wayland_probe();
    let cli = Cli::parse();
    let command = match (cli.command, cli.markdown_help) {
        (_, true) => {
            clap_markdown::print_help_markdown::<Cli>();
            return ExitCode::SUCCESS;
        }
        (Some(command), false) => command,
        (None, false) => {
            eprintln!("{}", Cli::command().render_help());
            return ExitCode::from(2);
        }
    };
    let result = match command {
        Command::Render(args) => commands::render::run(args),
        Command::Perturb(args) => commands::perturb::run(args),
        Command::List(args) => commands::list::run(args),
        Command::Scene(args) => commands::scene::run(args),
        Command::Eval(args) => commands::eval::run(args),
        Command::Verify(args) => commands::verify::run(args),
        Command::Suite(args) => commands::suite::run(args),
        Command::View(args) => commands::view::run(args),
    };
    match result {
        Ok(code) => code,
        Err(error) => {
            eprintln!("error: {}", flags::worded(&error));
            ExitCode::from(2)
        }
    }
}
