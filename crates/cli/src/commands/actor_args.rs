//! `--actor MESH PATH`, as `rslam render` and `rslam view` take it.

use std::path::PathBuf;

use rslam_pipeline::ActorFiles;

#[derive(clap::Args, Clone, Debug, Default)]
pub struct ActorArgs {
    /// An actor of your own: MESH (PLY, OBJ or glTF; z up, its origin where it meets the floor)
    /// moved along PATH (a trajectory file, each pose the mesh's frame in the world; linear
    /// between poses, at rest outside them). Repeat for more; each gets the next instance-mask
    /// id, and walkers and objects give way to them. Needs a built-in scene.
    #[arg(long, num_args = 2, value_names = ["MESH", "PATH"], action = clap::ArgAction::Append)]
    actor: Vec<PathBuf>,
}

impl ActorArgs {
    pub fn files(&self) -> Vec<ActorFiles> {
        (self.actor.chunks_exact(2))
            .map(|pair| ActorFiles {
                mesh: pair[0].clone(),
                path: pair[1].clone(),
            })
            .collect()
    }
}
