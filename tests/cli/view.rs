use std::process::Command;

use crate::harness::Workspace;

#[test]
fn view_flags_that_cannot_work_are_one_line_naming_the_flag() {
    let ws = Workspace::new();
    ws.rslam(&["view"])
        .fails_with(2, &["give a DATASET folder or --scene"]);
    ws.rslam(&["view", "no_such_dir"])
        .fails_with(2, &["no_such_dir: no such dataset folder"]);
    ws.rslam(&["view", "--scene", "room0", "--perturb", "fogg:2"])
        .fails_with(2, &["--perturb", "fogg"]);
    ws.rslam(&["view", "--scene", "room0", "--estimate", "est.txt"])
        .fails_with(2, &["--estimate est.txt: no such file"]);
    ws.rslam(&["view", "--scene", "room0", "--camera", "1,2"])
        .fails_with(2, &["--camera"]);
}

/// `rslam view ARGS --screenshot SHOT` in a 900 × 600 window under Xvfb.
fn view_under_xvfb(ws: &Workspace, args: &[&str]) -> (std::process::Output, std::path::PathBuf) {
    let shot = ws.path("shot.png");
    let output = Command::new("xvfb-run")
        .args([
            "--auto-servernum",
            "--server-args=-screen 0 1000x700x24 -ac",
        ])
        .arg(env!("CARGO_BIN_EXE_rslam"))
        .arg("view")
        .args(args)
        .args(["--window", "900", "600", "--screenshot"])
        .arg(&shot)
        .current_dir(ws.path("."))
        .output()
        .expect("xvfb-run (apt-get install xvfb; scripts/install-system-deps.sh installs it)");
    (output, shot)
}

/// The real program in a real window: Xvfb is a virtual X server, lavapipe renders; the window
/// captures itself once the first frame is up and closes.
#[test]
fn view_opens_a_window_under_xvfb_and_saves_a_screenshot() {
    let ws = Workspace::new();
    let args = [
        "--scene",
        "room0",
        "--frames",
        "3",
        "--camera",
        "160,90,80,80,79.5,44.5",
        "--perturb",
        "fog:2",
    ];
    let (output, shot) = view_under_xvfb(&ws, &args);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "rslam view under Xvfb failed:\n{stderr}"
    );
    let image = image::open(&shot).unwrap_or_else(|e| panic!("{}: {e}\n{stderr}", shot.display()));
    assert_eq!((image.width(), image.height()), (900, 600), "{stderr}");
}

/// `--actor MESH PATH` previews a user's actor beside walkers and objects; a mesh that is not
/// there is one line naming it.
#[test]
fn view_previews_a_users_actor_beside_walkers_and_objects() {
    let ws = Workspace::new();
    ws.write("box.ply", crate::actors::BOX_PLY);
    // Where a pushed chair came to rest in office1, still.
    ws.write("still.txt", "0 2.66 -0.09 0 0 0 0 1\n");
    let scene = [
        "--scene",
        "office1",
        "--frames",
        "40",
        "--camera",
        "160,90,80,80,79.5,44.5",
    ];
    let with = |mesh: &str| {
        let mut args = scene.to_vec();
        args.extend([
            "--perturb",
            "actors:1,objects:1",
            "--actor",
            mesh,
            "still.txt",
        ]);
        let (output, _) = view_under_xvfb(&ws, &args);
        String::from_utf8_lossy(&output.stderr).to_string()
    };
    let fine = with("box.ply");
    assert!(!fine.contains("error"), "{fine}");
    let missing = with("missing.ply");
    assert!(missing.contains("error: missing.ply"), "{missing}");
}
