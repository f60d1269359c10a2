use std::process::ExitCode;

use rslam_perturb::{listing, ListEntry};

#[derive(clap::Args)]
pub struct ListArgs {
    /// Print the list as JSON (name, group, syntax, description, parameters per severity).
    #[arg(long)]
    json: bool,
}

pub fn run(args: ListArgs) -> anyhow::Result<ExitCode> {
    let entries = listing();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&entries)?);
    } else {
        print!("{}", text(&entries));
    }
    Ok(ExitCode::SUCCESS)
}

const HEADINGS: [(&str, &str); 7] = [
    ("image", "Image corruptions (severity 1-5 or low/mid/high; @dynamic: per-frame severity uniform in 0..s)"),
    ("depth", "Depth corruptions (0 = invalid depth, stays invalid)"),
    ("trajectory", "Trajectory deviations (frames re-rendered along the deviated poses)"),
    ("stream", "Stream operations"),
    ("sensor", "Sensor effects (the image formed from the camera's motion during capture; need a scene)"),
    ("calibration", "Calibration of a rig (--rig, or a EuRoC input with @calibration); image and depth items also take a camera: cam1:fog:3"),
    ("imu", "IMU items (need an IMU: `render --rig stereo-imu --format euroc` or `--rig rgbd-imu --format tum`, or a EuRoC dataset with imu0/)"),
];

fn text(entries: &[ListEntry]) -> String {
    let mut out = String::new();
    for (group, heading) in HEADINGS {
        out.push_str(&format!("{heading}\n"));
        for e in entries.iter().filter(|e| e.group == group) {
            out.push_str(&format!("  {:<20} {}\n", e.name, e.description));
            out.push_str(&format!("  {:<20} syntax: {}\n", "", e.syntax));
            if !e.parameters.is_empty() {
                out.push_str(&format!(
                    "  {:<20} 1..5:   {}\n",
                    "",
                    e.parameters.join(" | ")
                ));
            }
        }
        out.push('\n');
    }
    out
}
