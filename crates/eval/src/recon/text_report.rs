//! The console report of one reconstruction evaluation: what was read, how it was culled, then
//! the three metrics, a name, a tab and the value.

use super::{Culling, ReconMetrics, SurfaceKind, SurfaceSummary, OCCLUSION_TOLERANCE_M};

pub fn recon_text_report(m: &ReconMetrics) -> String {
    let threshold = m.options.threshold_cm;
    format!(
        "reconstruction\t{}\nground truth\t{}\nseed\t{}\nculling\t{}\n\n\
         accuracy (cm)\t{:.4}\ncompletion (cm)\t{:.4}\ncompletion ratio (< {threshold} cm, %)\t{:.2}\n",
        describe(&m.reconstruction),
        describe(&m.ground_truth),
        m.options.seed,
        culling(m),
        m.accuracy_cm,
        m.completion_cm,
        m.completion_ratio_percent,
    )
}

fn culling(m: &ReconMetrics) -> String {
    let what = match m.options.culling {
        Culling::None => return "none: every sampled point".into(),
        Culling::Frustum => "frustum: points inside a ground-truth camera's view".to_string(),
        Culling::Visible => format!(
            "visible: points a ground-truth camera saw past the ground-truth mesh ({} cm tolerance)",
            OCCLUSION_TOLERANCE_M * 100.0
        ),
    };
    format!(
        "{what}, {} views; kept {:.1} % of the reconstruction's samples, {:.1} % of the ground truth's",
        m.views,
        m.reconstruction.kept_percent(),
        m.ground_truth.kept_percent()
    )
}

fn describe(s: &SurfaceSummary) -> String {
    match s.kind {
        SurfaceKind::Mesh => format!(
            "{}: mesh, {} vertices, {} triangles, {} points sampled on its surface",
            s.path.display(),
            s.vertices,
            s.triangles,
            s.samples
        ),
        SurfaceKind::PointCloud => format!(
            "{}: point cloud, {} points, {} of them used as samples",
            s.path.display(),
            s.vertices,
            s.samples
        ),
    }
}
