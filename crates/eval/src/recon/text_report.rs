//! The console report of one reconstruction evaluation: what was read, then the three metrics,
//! a name, a tab and the value.

use super::{ReconMetrics, SurfaceKind, SurfaceSummary};

pub fn recon_text_report(m: &ReconMetrics) -> String {
    let threshold = m.options.threshold_cm;
    format!(
        "reconstruction\t{}\nground truth\t{}\nseed\t{}\n\n\
         accuracy (cm)\t{:.4}\ncompletion (cm)\t{:.4}\ncompletion ratio (< {threshold} cm, %)\t{:.2}\n",
        describe(&m.reconstruction),
        describe(&m.ground_truth),
        m.options.seed,
        m.accuracy_cm,
        m.completion_cm,
        m.completion_ratio_percent,
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
