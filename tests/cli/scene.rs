//! `rslam scene`: export the ground-truth mesh, write the default trajectory, list scenes.

use crate::harness::Workspace;

/// Vertex and face counts from a PLY header, and the header's length in bytes.
fn ply_counts(bytes: &[u8]) -> (usize, usize, usize) {
    let end = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .expect("PLY header")
        + 11;
    let header = String::from_utf8_lossy(&bytes[..end]);
    let count = |element: &str| {
        header
            .lines()
            .find_map(|l| l.strip_prefix(&format!("element {element} ")))
            .and_then(|n| n.trim().parse().ok())
            .expect("element count")
    };
    (count("vertex"), count("face"), end)
}

#[test]
fn traj_writes_2000_replica_poses() {
    let ws = Workspace::new();
    let out = ws
        .rslam(&["scene", "traj", "room0", "--out", "traj.txt"])
        .success();
    assert!(out.contains("2000 poses"), "{out}");
    let text = std::fs::read_to_string(ws.path("traj.txt")).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 2000);
    for row in &rows {
        assert_eq!(row.len(), 16);
        assert_eq!(&row[12..], &[0.0, 0.0, 0.0, 1.0]);
        // Camera height (row-major z translation) is hand-held, inside the room.
        assert!((1.0..2.0).contains(&row[11]), "height {}", row[11]);
    }
    let first_step: f64 = (0..3)
        .map(|k| (rows[1][4 * k + 3] - rows[0][4 * k + 3]).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!(
        first_step > 0.0 && first_step < 0.05,
        "smooth motion at 20 Hz: {first_step} m"
    );
}

#[test]
fn export_writes_a_binary_triangle_ply_of_the_builtin_scene() {
    let ws = Workspace::new();
    let out = ws
        .rslam(&["scene", "export", "office1", "--out", "gt.ply"])
        .success();
    assert!(
        out.contains("triangles") && out.contains("content hash"),
        "{out}"
    );
    let bytes = std::fs::read(ws.path("gt.ply")).unwrap();
    assert!(bytes.starts_with(b"ply\nformat binary_little_endian 1.0\n"));
    let (vertices, faces, header) = ply_counts(&bytes);
    assert!(faces > 10_000, "{faces} triangles");
    // 3 floats + 3 colour bytes per vertex; count byte + 3 ints per face.
    assert_eq!(bytes.len(), header + vertices * 15 + faces * 13);
}

#[test]
fn export_of_a_user_mesh_and_its_missing_trajectory() {
    let ws = Workspace::new();
    ws.write(
        "tri.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
         element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    );
    ws.rslam(&["scene", "export", "tri.ply", "--out", "gt.ply"])
        .success();
    let (vertices, faces, _) = ply_counts(&std::fs::read(ws.path("gt.ply")).unwrap());
    assert_eq!((vertices, faces), (3, 1));
    ws.rslam(&["scene", "traj", "tri.ply", "--out", "traj.txt"])
        .fails_with(2, &["tri.ply", "no default trajectory", "room0"]);
    assert!(!ws.path("traj.txt").exists());
}

#[test]
fn bad_scenes_and_paths_are_one_line_errors() {
    let ws = Workspace::new();
    ws.rslam(&["scene", "export", "kitchen9", "--out", "gt.ply"])
        .fails_with(2, &["unknown scene 'kitchen9'", "office4"]);
    ws.rslam(&["scene", "export", "missing.obj", "--out", "gt.ply"])
        .fails_with(2, &["missing.obj"]);
    ws.write("cut.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n\x01");
    ws.rslam(&["scene", "export", "cut.ply", "--out", "gt.ply"])
        .fails_with(2, &["cut.ply", "declares 2 records"]);
    ws.rslam(&["scene", "export", "room1", "--out", "no/such/dir/gt.ply"])
        .fails_with(2, &["no/such/dir/gt.ply"]);
}

#[test]
fn list_names_every_builtin_scene() {
    let out = Workspace::new().rslam(&["scene", "list"]).success();
    let names: Vec<&str> = out.lines().collect();
    assert_eq!(
        names,
        ["room0", "room1", "room2", "office0", "office1", "office2", "office3", "office4"]
    );
}

#[test]
fn stats_measure_every_kth_frame_of_a_dataset_and_reject_a_zero_step() {
    let ws = Workspace::new();
    ws.rslam(&[
        "render",
        "--scene",
        "room0",
        "--frames",
        "5",
        "--camera",
        "160,90,80,80,79.5,44.5",
        "--out",
        "d",
    ])
    .success();
    let out = ws
        .rslam(&[
            "scene",
            "stats",
            "d",
            "--every",
            "2",
            "--json",
            "stats.json",
        ])
        .success();
    assert!(out.contains("3 frames of d"), "{out}");
    assert!(out.contains("FAST corners (threshold 20)"), "{out}");
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(ws.path("stats.json")).unwrap()).unwrap();
    let frames: Vec<u64> = doc["frames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["frame"].as_u64().unwrap())
        .collect();
    assert_eq!(frames, vec![0, 2, 4]);
    for f in doc["frames"].as_array().unwrap() {
        let s = &f["stats"];
        assert!(
            s["fast_corners"].as_u64().unwrap() > 0,
            "a furnished room has corners: {s}"
        );
        let low = s["low_texture_cells"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&low), "{s}");
    }
    ws.rslam(&["scene", "stats", "d", "--every", "0"])
        .fails_with(2, &["--every", "at least 1"]);
}

#[test]
fn stats_measure_every_photograph_of_a_folder_beside_the_real_photographs_band() {
    let ws = Workspace::new();
    std::fs::create_dir(ws.path("photos")).unwrap();
    // A 40-grey square of side 20 on grey 10 at (10, 10): four corners of strength 30, under
    // the strong-corner bar of 35; then the same square at grey 210: strength 200.
    for (name, square) in [("a.png", 40u8), ("b.png", 210)] {
        let image = image::GrayImage::from_fn(48, 40, |x, y| {
            let inside = (10..30).contains(&x) && (10..30).contains(&y);
            image::Luma([if inside { square } else { 10 }])
        });
        image.save(ws.path(&format!("photos/{name}"))).unwrap();
    }
    let out = ws
        .rslam(&["scene", "stats", "photos", "--json", "stats.json"])
        .success();
    assert!(out.contains("2 frames of photos"), "{out}");
    assert!(out.contains("real photographs"), "{out}");
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(ws.path("stats.json")).unwrap()).unwrap();
    let stat = |i: usize, key: &str| doc["frames"][i]["stats"][key].as_f64().unwrap();
    assert_eq!(
        (stat(0, "corner_strength_p50"), stat(0, "strong_corners")),
        (30.0, 0.0)
    );
    assert_eq!(
        (stat(1, "corner_strength_p50"), stat(1, "strong_corners")),
        (200.0, 1.0)
    );
    // 4 corners on 48 × 40 pixels.
    let density = 4.0 * 1e4 / (48.0 * 40.0);
    assert!((stat(1, "weak_corner_density") - density).abs() < 1e-3);
}
