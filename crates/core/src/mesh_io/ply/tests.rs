use super::*;

/// A Replica-style binary PLY: normals, uchar colours, two quads sharing an edge.
fn replica_style(big_endian: bool) -> Vec<u8> {
    let format = if big_endian {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut b = format!(
        "ply\nformat {format} 1.0\ncomment like Replica's mesh.ply\nelement vertex 6\n\
         property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n\
         element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    )
    .into_bytes();
    let f = |b: &mut Vec<u8>, v: f32| {
        b.extend(if big_endian {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        })
    };
    let i = |b: &mut Vec<u8>, v: i32| {
        b.extend(if big_endian {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        })
    };
    for k in 0..6 {
        let (x, y) = ((k % 3) as f32, (k / 3) as f32);
        for c in [x, y, 1.5, 0.0, 0.0, 1.0] {
            f(&mut b, c);
        }
        b.extend([10 * k as u8, 20, 30, 255]);
    }
    for quad in [[0, 1, 4, 3], [1, 2, 5, 4]] {
        b.push(4);
        for v in quad {
            i(&mut b, v);
        }
    }
    b
}

#[test]
fn reads_binary_quads_with_colours_in_both_byte_orders() {
    for big in [false, true] {
        let mesh = parse_ply(&replica_style(big)).unwrap();
        assert_eq!(mesh.positions.len(), 6);
        assert_eq!(
            mesh.indices,
            vec![0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4],
            "quads become fans"
        );
        assert_eq!(mesh.positions[4], [1.0, 1.0, 1.5]);
        assert_eq!(mesh.colors.unwrap()[5], [50, 20, 30]);
    }
}

#[test]
fn reads_ascii_triangles_with_float_colours_and_extra_elements() {
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n\
                property float red\nproperty float green\nproperty float blue\n\
                element face 1\nproperty uchar flags\nproperty list uchar uint vertex_index\n\
                element edge 1\nproperty int a\nproperty int b\nend_header\n\
                0 0 0 1 0 0\n1 0 0 0 1 0\n0 1 0  0 0 0.5\n7 3 0 1 2\n0 1\n";
    let mesh = parse_ply(text.as_bytes()).unwrap();
    assert_eq!(mesh.indices, vec![0, 1, 2]);
    let colors = mesh.colors.unwrap();
    assert_eq!(colors[0], [255, 0, 0]);
    assert_eq!(colors[2], [0, 0, 128]);
}

#[test]
fn vertices_without_faces_read_as_a_point_cloud_without_colours() {
    let text = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n\
                property float intensity\nend_header\n0 0 0 7\n1 2 3 8\n";
    let cloud = parse_ply(text.as_bytes()).unwrap();
    assert_eq!(cloud.positions, vec![[0.0; 3], [1.0, 2.0, 3.0]]);
    assert!(cloud.is_point_cloud());
    assert_eq!(cloud.colors, None);
}

fn header_len(bytes: &[u8]) -> usize {
    bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .unwrap()
        + 11
}

#[test]
fn bad_files_give_one_line_errors_naming_the_problem() {
    let full = replica_style(false);
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (full[..full.len() - 5].to_vec(), "file ends early in element 'face' record 1 of 2"),
        (full[..header_len(&full) + 50].to_vec(), "element 'vertex' declares 6 records, but the rest of the file holds at most 1"),
        (b"solid cube\nfacet normal 0 0 1\n".to_vec(), "no 'end_header'"),
        (b"plx\nformat ascii 1.0\nend_header\n".to_vec(), "first line is not 'ply'"),
        (b"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n0\n".to_vec(), "header line 4: unknown property type"),
        (b"ply\nformat zip 1.0\nend_header\n".to_vec(), "unknown format"),
        // Found by fuzzing: a carriage return inside a header line was quoted as is.
        (b"ply\nformat ascii 1.0\nprope\rty float z\nend_header\n".to_vec(), "unrecognised header line: 'prope\\rty float z'"),
        (
            b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n3 0 1 2\n".to_vec(),
            "face 0 refers to vertex 1 but the file has 1 vertices",
        ),
        (b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\nabc 0 0\n".to_vec(), "'abc' is not a number"),
        (b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float z\nend_header\n0 0\n".to_vec(), "the 'vertex' element has no 'y' property"),
        // Found by fuzzing: a second 'opacity' column in a splat capture read as two values a Gaussian.
        (b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float y\nproperty float z\nend_header\n0 0 0 0\n".to_vec(), "header line 6: property declared twice in one element: 'property float y'"),
        (b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 nan 0\n".to_vec(), "vertex 0: coordinate y = NaN is not a finite 32-bit float"),
        (b"ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nproperty double y\nproperty double z\nend_header\n0 0 1e300\n".to_vec(), "vertex 0: coordinate z = 1e300 is not a finite 32-bit float"),
    ];
    for (bytes, expected) in cases {
        let err = parse_ply(&bytes).unwrap_err();
        assert!(err.contains(expected), "expected '{expected}' in '{err}'");
        assert!(!err.contains('\n'), "one line: {err}");
    }
}

/// Headers that claim more than the file holds, or more than rslam accepts, are refused before
/// anything is allocated or looped over for them (before, a 10⁹-vertex header reserved 12 GB,
/// and an element of 10¹⁸ empty records looped that many times).
#[test]
fn claimed_counts_are_checked_before_they_are_believed() {
    let vertices = |count: &str| {
        format!(
            "ply\nformat binary_little_endian 1.0\nelement vertex {count}\nproperty float x\n\
             property float y\nproperty float z\nend_header\n"
        )
        .into_bytes()
    };
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (vertices("1000000000"), "declares 1000000000 vertices, over the limit of 100000000"),
        (vertices("99999999"), "element 'vertex' declares 99999999 records, but the rest of the file holds at most 0"),
        (
            b"ply\nformat ascii 1.0\nelement face 5000000\nproperty list uchar int vertex_indices\nend_header\n3 0 1 2\n".to_vec(),
            "element 'face' declares 5000000 records, but the rest of the file holds at most 4",
        ),
        (
            b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list int int vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0\n2000000000 0 1 2\n".to_vec(),
            "face 0 has 2000000000 corners; expected 0 to 1000",
        ),
        (
            b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nproperty list int int extra\nend_header\n0 0 0 -5\n".to_vec(),
            "list length -5 is negative",
        ),
    ];
    for (bytes, expected) in cases {
        let err = parse_ply(&bytes).unwrap_err();
        assert!(err.contains(expected), "expected '{expected}' in '{err}'");
    }
    let empty_records = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
                          element nothing 1000000000000000000\nend_header\n0 0 0 1 0 0 0 1 0\n";
    assert_eq!(parse_ply(empty_records).unwrap().positions.len(), 3);
}

/// A header comment holding the words `end_header` (the export writes the scene's name there)
/// ended the header early; found while writing the export round-trip property, which tries it.
#[test]
fn only_an_end_header_line_ends_the_header() {
    let bytes =
        b"ply\nformat ascii 1.0\ncomment scene 'end_header'\nelement vertex 1\nproperty float x\n\
                  property float y\nproperty float z\nend_header\n1 2 3\n";
    assert_eq!(parse_ply(bytes).unwrap().positions, vec![[1.0, 2.0, 3.0]]);
}
