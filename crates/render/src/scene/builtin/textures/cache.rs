//! Generated textures on disk. Painting a built-in scene's textures is most of the time it takes
//! to build (about a second of CPU for room0), and every process that draws the scene would paint
//! them again. A file holds one texture's texels and a BLAKE3 digest of them, checked on load; it
//! lies in `textures/<generator>/` of the cache folder, where the generator is named by a hash of
//! the generator's source files (made by build.rs) and a probe of the maths library the patterns
//! call, so a changed generator or library never reads what another made. Only one generator's
//! folder is kept: the first texture stored under a new one removes the others. The cache only
//! saves time: a missing, unwritable or damaged file means painting the texture again.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use rslam_core::hash::fnv1a64;

use super::{TextureSpec, TEXTURE_SIZE};
use crate::Texture;

/// The hash of the generator's source files, from build.rs.
const GENERATOR_SOURCE: &str = env!("RSLAM_TEXTURE_GENERATOR");

const DIGEST_BYTES: usize = 32;

/// The texture `spec` paints, from the cache when it holds it.
pub fn texture(spec: &TextureSpec) -> Texture {
    match super::super::cache_root() {
        Some(root) => cached(&root.join("textures"), spec),
        None => spec.generate(),
    }
}

/// [`texture`] with the cache's `textures/` folder at `textures`.
fn cached(textures: &Path, spec: &TextureSpec) -> Texture {
    let folder = textures.join(generator());
    let path = folder.join(file_name(spec));
    if let Some(texture) = load(&path) {
        return texture;
    }
    let texture = spec.generate();
    store(textures, &folder, &path, &texture);
    texture
}

/// The generator's name: its source and the maths library it runs on.
fn generator() -> &'static str {
    static NAME: OnceLock<String> = OnceLock::new();
    NAME.get_or_init(|| format!("{GENERATOR_SOURCE}-{:016x}", maths_probe()))
}

/// A hash of what the maths functions the patterns call return on this machine (they come from
/// the system's maths library, which an update may change in the last bit).
fn maths_probe() -> u64 {
    let mut bytes = Vec::new();
    for i in 0..64 {
        let x = i as f32 * 0.731 - 9.0;
        let values = [
            x.sin(),
            x.cos(),
            x.exp(),
            x.abs().ln(),
            x.abs().powf(1.7),
            x.atan2(1.3),
            x.sqrt(),
            x.floor(),
            x.round(),
            x % 0.37,
        ];
        bytes.extend(values.iter().flat_map(|v| v.to_bits().to_le_bytes()));
    }
    fnv1a64(&bytes)
}

fn file_name(spec: &TextureSpec) -> String {
    format!("{:?}-{:016x}-{TEXTURE_SIZE}.rgba", spec.pattern, spec.seed)
}

fn texel_bytes() -> usize {
    TEXTURE_SIZE as usize * TEXTURE_SIZE as usize * 4
}

/// The texture in `path`, if it is whole: the right size and its digest matching.
fn load(path: &Path) -> Option<Texture> {
    let mut bytes = std::fs::read(path).ok()?;
    if bytes.len() != texel_bytes() + DIGEST_BYTES {
        return None;
    }
    let digest = bytes.split_off(texel_bytes());
    if blake3::hash(&bytes).as_bytes()[..] != digest[..] {
        return None;
    }
    Some(Texture {
        width: TEXTURE_SIZE,
        height: TEXTURE_SIZE,
        rgba: bytes,
    })
}

/// Keeps `texture` in `path` (written under a name of this process's, then renamed, so that a
/// reader never sees part of a file); a new generator folder removes the other generators'.
/// Failures only cost painting it again next time.
fn store(textures: &Path, folder: &Path, path: &Path, texture: &Texture) {
    if std::fs::create_dir_all(textures).is_err() {
        return;
    }
    if std::fs::create_dir(folder).is_ok() {
        remove_other_generators(textures, folder);
    }
    let mut partial = PathBuf::from(path.as_os_str());
    partial
        .as_mut_os_string()
        .push(format!(".{}.partial", std::process::id()));
    let digest = blake3::hash(&texture.rgba);
    let written = std::fs::File::create(&partial).and_then(|mut file| {
        file.write_all(&texture.rgba)?;
        file.write_all(digest.as_bytes())
    });
    if written.is_err() || std::fs::rename(&partial, path).is_err() {
        let _ = std::fs::remove_file(&partial);
    }
}

fn remove_other_generators(textures: &Path, current: &Path) {
    let Ok(entries) = std::fs::read_dir(textures) else {
        return;
    };
    for entry in entries.flatten() {
        if entry.path() != current {
            let _ = std::fs::remove_dir_all(entry.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::Pattern;
    use super::*;

    const SPEC: TextureSpec = TextureSpec {
        pattern: Pattern::Fabric,
        seed: 7,
    };

    #[test]
    fn a_cached_texture_is_the_painted_one_and_a_damaged_file_is_painted_again() {
        let dir = tempfile::tempdir().unwrap();
        let textures = dir.path().join("textures");
        let painted = SPEC.generate();
        assert_eq!(
            cached(&textures, &SPEC),
            painted,
            "first: painted and stored"
        );
        let path = textures.join(generator()).join(file_name(&SPEC));
        assert_eq!(load(&path).as_ref(), Some(&painted), "stored whole");
        assert_eq!(cached(&textures, &SPEC), painted, "second: read back");

        let mut bytes = std::fs::read(&path).unwrap();
        bytes[1000] ^= 1;
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(load(&path), None, "a flipped bit fails the digest");
        assert_eq!(cached(&textures, &SPEC), painted, "painted again");
        assert_eq!(load(&path).as_ref(), Some(&painted), "and stored again");

        bytes.truncate(bytes.len() - 1);
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(load(&path), None, "a short file is not read");
    }

    #[test]
    fn another_generators_folder_is_removed_and_never_read() {
        let dir = tempfile::tempdir().unwrap();
        let textures = dir.path().join("textures");
        let old = textures.join("0123456789abcdef-0000000000000000");
        std::fs::create_dir_all(&old).unwrap();
        let mut stale = Texture::white();
        stale.rgba = vec![9; texel_bytes()];
        let mut bytes = stale.rgba.clone();
        bytes.extend_from_slice(blake3::hash(&stale.rgba).as_bytes());
        std::fs::write(old.join(file_name(&SPEC)), bytes).unwrap();
        assert_eq!(cached(&textures, &SPEC), SPEC.generate());
        assert!(!old.exists(), "the other generator's folder is gone");
        assert!(textures.join(generator()).join(file_name(&SPEC)).exists());
    }
}
