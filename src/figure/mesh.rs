//! A link's look from the user's own CAD parts: a triangle mesh read from an
//! STL file (binary or ASCII, by `stl_io`) or an OBJ file (by `tobj`, with its
//! normals where it gives them), in the file's own units. What cannot be read
//! is a [`MeshError`] that says which file and why; the figure then draws the
//! link as it would without a mesh.

use std::path::{Path, PathBuf};

use super::Vec3;

/// Triangles, each with its facing.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// The corners.
    pub positions: Vec<Vec3>,
    /// Each triangle's corners (indices into `positions`), counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Each triangle's outward normal (unit).
    pub normals: Vec<Vec3>,
}

/// A file's bytes read as a mesh, or its kind and what was wrong.
pub type Parsed = Result<Mesh, (&'static str, String)>;

/// Why a mesh file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The file could not be opened or read.
    #[error("cannot read the mesh {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file is not a mesh of its kind.
    #[error("{path} is not a readable {kind} file: {reason}")]
    Malformed {
        /// The file.
        path: PathBuf,
        /// "STL" or "OBJ".
        kind: &'static str,
        /// What the reader found.
        reason: String,
    },
    /// Not a regular file within [`MAX_MESH_BYTES`] (a named pipe, a device,
    /// a link to one): refused before reading.
    #[error("{why}")]
    Refused {
        /// The file.
        path: PathBuf,
        /// Why, naming it.
        why: String,
    },
    /// It holds no triangles.
    #[error("{path} holds no triangles")]
    Empty {
        /// The file.
        path: PathBuf,
    },
    /// Neither .stl nor .obj.
    #[error("{path}: only STL (.stl) and OBJ (.obj) meshes can be loaded")]
    Kind {
        /// The file.
        path: PathBuf,
    },
}

/// The largest mesh file read, bytes (2.6 million binary STL triangles: far
/// more than a servo robot's link needs).
pub const MAX_MESH_BYTES: u64 = 128 * 1024 * 1024;

/// The bytes of the mesh file `path`: a regular file within [`MAX_MESH_BYTES`]
/// only (never a pipe, a device or a link to one: refused before reading).
fn read_mesh_file(path: &Path) -> Result<Vec<u8>, MeshError> {
    use std::io::Read as _;
    let (file, length) = crate::project::input::open_regular(path, MAX_MESH_BYTES).map_err(|error| match error {
        crate::project::input::ReadError::Io { source, .. } => MeshError::Read { path: path.to_path_buf(), source },
        refused => MeshError::Refused { path: path.to_path_buf(), why: refused.to_string() },
    })?;
    let mut bytes = Vec::with_capacity(usize::try_from(length).unwrap_or(0));
    file.take(MAX_MESH_BYTES)
        .read_to_end(&mut bytes)
        .map_err(|source| MeshError::Read { path: path.to_path_buf(), source })?;
    Ok(bytes)
}

impl Mesh {
    /// Reads an `.stl` or `.obj` file.
    pub fn load(path: &Path) -> Result<Self, MeshError> {
        let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        let read: fn(&[u8]) -> Parsed = match extension.as_deref() {
            Some("stl") => Self::from_stl,
            Some("obj") => Self::from_obj,
            _ => return Err(MeshError::Kind { path: path.to_path_buf() }),
        };
        let bytes = read_mesh_file(path)?;
        let mesh = read(&bytes);
        let mesh = mesh.map_err(|(kind, reason)| MeshError::Malformed { path: path.to_path_buf(), kind, reason })?;
        if mesh.triangles.is_empty() {
            return Err(MeshError::Empty { path: path.to_path_buf() });
        }
        Ok(mesh)
    }

    /// An STL file's triangles (binary or ASCII).
    pub fn from_stl(bytes: &[u8]) -> Parsed {
        // A binary STL says how many triangles follow (50 bytes each): a
        // count the file cannot hold is refused before anything is made of it.
        let text = bytes.starts_with(b"solid") && bytes[..bytes.len().min(512)].iter().all(|b| b.is_ascii() && *b != 0);
        if !text && bytes.len() >= 84 {
            let count = u64::from(u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]));
            let room = (bytes.len() as u64 - 84) / 50;
            if count > room {
                return Err(("STL", format!("its header says {count} triangles, but the file holds only {room}")));
            }
        }
        let read = stl_io::read_stl(&mut std::io::Cursor::new(bytes)).map_err(|error| ("STL", error.to_string()))?;
        let positions: Vec<Vec3> = read.vertices.iter().map(|v| Vec3::from(v.0)).collect();
        let mut mesh = Self { positions, ..Self::default() };
        for face in &read.faces {
            let corners = face.vertices.map(|index| u32::try_from(index).unwrap_or(u32::MAX));
            if corners.iter().any(|&c| c as usize >= mesh.positions.len()) {
                return Err(("STL", "a triangle names a corner that is not there".into()));
            }
            mesh.push(corners, Some(Vec3::from(face.normal.0)));
        }
        Ok(mesh)
    }

    /// An OBJ file's faces (triangulated), with its normals where given.
    pub fn from_obj(bytes: &[u8]) -> Parsed {
        let options = tobj::LoadOptions { triangulate: true, single_index: true, ..tobj::LoadOptions::default() };
        let (models, _) = tobj::load_obj_buf(&mut std::io::Cursor::new(bytes), &options, |_| {
            // Materials are not used: the figure shades its own colour.
            Err(tobj::LoadError::GenericFailure)
        })
        .map_err(|error| ("OBJ", error.to_string()))?;
        let mut mesh = Self::default();
        for model in models {
            let base = u32::try_from(mesh.positions.len()).map_err(|_| ("OBJ", "too many corners".to_string()))?;
            let at = |list: &[f32], index: usize| Vec3::new(list[index * 3], list[index * 3 + 1], list[index * 3 + 2]);
            let count = model.mesh.positions.len() / 3;
            mesh.positions.extend((0..count).map(|index| at(&model.mesh.positions, index)));
            let normals = &model.mesh.normals;
            for corners in model.mesh.indices.chunks_exact(3) {
                if corners.iter().any(|&c| c as usize >= count) {
                    return Err(("OBJ", "a face names a corner that is not there".into()));
                }
                // The file's normals, where it gives them: their mean faces the triangle's way.
                let given = (normals.len() == model.mesh.positions.len())
                    .then(|| corners.iter().map(|&c| at(normals, c as usize)).sum::<Vec3>());
                mesh.push([corners[0] + base, corners[1] + base, corners[2] + base], given);
            }
        }
        Ok(mesh)
    }

    /// Adds a triangle; its normal from its corners (turned to agree with
    /// `given`'s side when the file gives one and they disagree).
    fn push(&mut self, corners: [u32; 3], given: Option<Vec3>) {
        let [a, b, c] = corners.map(|index| self.positions[index as usize]);
        let mut normal = (b - a).cross(c - a).normalize_or_zero();
        let mut corners = corners;
        if let Some(given) = given.filter(|g| g.length_squared() > 0.0)
            && normal.dot(given) < 0.0
        {
            // Wound the other way from what the file says faces out.
            corners.swap(1, 2);
            normal = -normal;
        }
        if normal == Vec3::ZERO {
            return;
        }
        self.triangles.push(corners);
        self.normals.push(normal);
    }

    /// The box around it: lowest and highest corners.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.positions
            .iter()
            .fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(low, high), p| (low.min(*p), high.max(*p)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube's 12 triangles as a binary STL (written here, byte by byte).
    fn binary_cube() -> Vec<u8> {
        let mut bytes = vec![0u8; 80];
        let triangles = cube();
        bytes.extend(u32::try_from(triangles.len()).unwrap().to_le_bytes());
        for (normal, corners) in &triangles {
            for v in std::iter::once(normal).chain(corners) {
                for c in v.to_array() {
                    bytes.extend(c.to_le_bytes());
                }
            }
            bytes.extend([0, 0]);
        }
        bytes
    }

    fn cube() -> Vec<(Vec3, [Vec3; 3])> {
        let p = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
        let quads = [
            (Vec3::Z, [p(0., 0., 1.), p(1., 0., 1.), p(1., 1., 1.), p(0., 1., 1.)]),
            (-Vec3::Z, [p(0., 0., 0.), p(0., 1., 0.), p(1., 1., 0.), p(1., 0., 0.)]),
            (Vec3::X, [p(1., 0., 0.), p(1., 1., 0.), p(1., 1., 1.), p(1., 0., 1.)]),
            (-Vec3::X, [p(0., 0., 0.), p(0., 0., 1.), p(0., 1., 1.), p(0., 1., 0.)]),
            (Vec3::Y, [p(0., 1., 0.), p(0., 1., 1.), p(1., 1., 1.), p(1., 1., 0.)]),
            (-Vec3::Y, [p(0., 0., 0.), p(1., 0., 0.), p(1., 0., 1.), p(0., 0., 1.)]),
        ];
        quads.iter().flat_map(|(n, q)| [(*n, [q[0], q[1], q[2]]), (*n, [q[0], q[2], q[3]])]).collect()
    }

    fn check_cube(mesh: &Mesh) {
        assert_eq!(mesh.triangles.len(), 12);
        let (low, high) = mesh.bounds();
        assert_eq!((low, high), (Vec3::ZERO, Vec3::ONE));
        // Every normal points out of the cube's middle.
        for (corners, normal) in mesh.triangles.iter().zip(&mesh.normals) {
            let centre = corners.iter().map(|&c| mesh.positions[c as usize]).sum::<Vec3>() / 3.0;
            assert!(normal.dot(centre - Vec3::splat(0.5)) > 0.0, "{normal} at {centre}");
        }
    }

    #[test]
    fn binary_and_ascii_stl_and_obj_with_normals_read_the_same_cube() {
        let dir = tempfile::tempdir().unwrap();
        let binary = dir.path().join("cube.stl");
        std::fs::write(&binary, binary_cube()).unwrap();
        check_cube(&Mesh::load(&binary).unwrap());

        let mut ascii = String::from("solid cube\n");
        for (n, corners) in cube() {
            ascii += &format!("facet normal {} {} {}\n outer loop\n", n.x, n.y, n.z);
            for v in corners {
                ascii += &format!("  vertex {} {} {}\n", v.x, v.y, v.z);
            }
            ascii += " endloop\nendfacet\n";
        }
        ascii += "endsolid cube\n";
        let path = dir.path().join("ascii.STL");
        std::fs::write(&path, ascii).unwrap();
        check_cube(&Mesh::load(&path).unwrap());

        // OBJ: corners and normals by index, faces as quads (triangulated), some wound inward.
        let mut obj = String::from("# a cube\n");
        let mut count = 0;
        for (n, corners) in cube().iter().step_by(2) {
            let quad = [corners[0], corners[1], corners[2], corners[0] + corners[2] - corners[1]];
            for v in quad {
                obj += &format!("v {} {} {}\nvn {} {} {}\n", v.x, v.y, v.z, n.x, n.y, n.z);
            }
            let i = count + 1;
            obj += &if count % 8 == 0 {
                format!("f {i}//{i} {}//{} {}//{} {}//{}\n", i + 1, i + 1, i + 2, i + 2, i + 3, i + 3)
            } else {
                format!("f {i}//{i} {}//{} {}//{} {}//{}\n", i + 3, i + 3, i + 2, i + 2, i + 1, i + 1)
            };
            count += 4;
        }
        let path = dir.path().join("cube.obj");
        std::fs::write(&path, obj).unwrap();
        check_cube(&Mesh::load(&path).unwrap());
    }

    #[test]
    fn a_malformed_or_missing_mesh_is_a_clear_error_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        // A binary STL that says 1000 triangles and holds 12.
        let mut truncated = binary_cube();
        truncated[80..84].copy_from_slice(&1000u32.to_le_bytes());
        let path = dir.path().join("arm.stl");
        std::fs::write(&path, &truncated).unwrap();
        let error = Mesh::load(&path).unwrap_err().to_string();
        assert!(error.contains("arm.stl") && error.contains("STL"), "{error}");

        let path = dir.path().join("leg.obj");
        std::fs::write(&path, "v 0 0 0\nv 1 0 0\nf 1 2 7\n").unwrap();
        let error = Mesh::load(&path).unwrap_err().to_string();
        assert!(error.contains("leg.obj"), "{error}");

        let missing = Mesh::load(&dir.path().join("gone.stl")).unwrap_err().to_string();
        assert!(missing.contains("gone.stl") && missing.contains("cannot read"), "{missing}");
        let kind = Mesh::load(&dir.path().join("x.ply")).unwrap_err();
        assert!(matches!(kind, MeshError::Kind { .. }), "{kind}");
    }
}
