use std::process::ExitCode;

use rslam_perturb::{listing, ListEntry};

#[derive(clap::Args)]
pub struct ListArgs {
    /// Print the list as JSON (name, group, syntax, description, needs, parameters per severity,
    /// how real severities are made).
    #[arg(long, conflicts_with = "markdown")]
    json: bool,
    /// Print the list as the book's catalogue page (docs/src/reference/catalogue.md).
    #[arg(long)]
    markdown: bool,
}

pub fn run(args: ListArgs) -> anyhow::Result<ExitCode> {
    let entries = listing();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&entries)?);
    } else if args.markdown {
        print!("{}", markdown(&entries));
    } else {
        print!("{}", text(&entries));
    }
    Ok(ExitCode::SUCCESS)
}

/// Each group's heading: its name, and where its items apply.
const HEADINGS: [(&str, &str, &str); 9] = [
    ("image", "Image corruptions", "severity 0-5 (0: the clean frame; real ones such as 2.5 where the item interpolates) or low/mid/high; @dynamic: per-frame severity uniform in 0..s"),
    ("depth", "Depth corruptions", "0 = invalid depth, stays invalid"),
    ("trajectory", "Trajectory deviations", "frames re-rendered along the deviated poses"),
    ("stream", "Stream operations", ""),
    ("sensor", "Sensor effects", "the image formed from the camera's motion during capture"),
    ("light", "Light", "built-in scenes: each lamp and the daylight is a layer of the bake, mixed per render with the light of the time it exposes"),
    ("world", "A world that moves", "built-in scenes: people on their free floor, drawn into every render at its instant"),
    ("calibration", "Calibration of a rig", "--rig, or a EuRoC input with @calibration; image and depth items also take a camera: cam1:fog:3"),
    ("imu", "IMU items", "need an IMU: `render --rig stereo-imu --format euroc` or `--rig rgbd-imu --format tum`, or a EuRoC dataset with imu0/"),
];

fn text(entries: &[ListEntry]) -> String {
    let mut out = String::new();
    for (group, name, applies) in HEADINGS {
        match applies {
            "" => out.push_str(&format!("{name}\n")),
            _ => out.push_str(&format!("{name} ({applies})\n")),
        }
        for e in entries.iter().filter(|e| e.group == group) {
            out.push_str(&format!("  {:<20} {}\n", e.name, e.description));
            out.push_str(&format!("  {:<20} syntax: {}\n", "", e.syntax));
            if !e.needs.is_empty() {
                out.push_str(&format!("  {:<20} needs:  {}\n", "", e.needs.join(", ")));
            }
            if !e.parameters.is_empty() {
                out.push_str(&format!(
                    "  {:<20} 1..5:   {}\n",
                    "",
                    e.parameters.join(" | ")
                ));
            }
            if !e.between.is_empty() {
                out.push_str(&format!("  {:<20} 2.5:    {}\n", "", e.between));
            }
        }
        out.push('\n');
    }
    out
}

/// The catalogue as a page of the book: a section per group, an entry per item with its syntax,
/// what it does and its parameters at each severity.
fn markdown(entries: &[ListEntry]) -> String {
    let mut out = String::from(
        "# Perturbation catalogue\n\nEvery item `--perturb` takes, generated from the catalogue by `rslam list --markdown` \
         (a test fails when this page differs from what the binary prints). The grammar, the \
         randomness and the benchmark's settings are in [Perturbations](../perturbations.md).\n",
    );
    for (group, name, applies) in HEADINGS {
        out.push_str(&format!("\n## {name}\n\n"));
        if !applies.is_empty() {
            out.push_str(&format!("{}.\n\n", capitalised(applies)));
        }
        for e in entries.iter().filter(|e| e.group == group) {
            out.push_str(&format!(
                "### `{}`\n\n{}\n\nSyntax: `{}`\n",
                e.name, e.description, e.syntax
            ));
            if !e.needs.is_empty() {
                out.push_str(&format!("\nNeeds {}.\n", e.needs.join(", ")));
            }
            if !e.parameters.is_empty() {
                out.push_str("\n| severity | parameters |\n|---|---|\n");
                for (s, p) in e.parameters.iter().enumerate() {
                    out.push_str(&format!("| {} | {} |\n", s + 1, p.replace('|', "\\|")));
                }
            }
            if !e.between.is_empty() {
                out.push_str(&format!("\nBetween whole severities: {}.\n", e.between));
            }
            out.push('\n');
        }
    }
    out.truncate(out.trim_end().len());
    out.push('\n');
    out
}

fn capitalised(text: &str) -> String {
    let mut chars = text.chars();
    chars
        .next()
        .map(|c| c.to_uppercase().chain(chars).collect())
        .unwrap_or_default()
}
