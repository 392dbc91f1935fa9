//! Meshes drawn by the graphics card, through eframe's OpenGL painter: each
//! mesh is uploaded once (its triangles, flat-shaded by their normals) and
//! every frame only asks for it to be drawn where its link is, with a depth
//! buffer, so a CAD part of 100k triangles costs the frame a few matrices.
//! Without OpenGL (headless tests, another renderer) nothing is drawn here
//! and the figure shows its links as boxes and rods instead (`View::show`
//! decides).
//!
//! OpenGL calls are `unsafe` in `glow`: this module is the one place the
//! crate allows it, and every call is made on the painter's own context
//! inside its paint callback, as `glow` requires.
#![allow(unsafe_code)]

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use eframe::egui_glow;
use eframe::glow::{self, HasContext};
use glam::{Mat3, Mat4, Vec3};

use crate::figure::mesh::Mesh;

/// One mesh to draw: its triangles, where it is (model matrix), its colour (0–1).
#[derive(Clone, Debug)]
pub struct Item {
    /// The triangles.
    pub mesh: Arc<Mesh>,
    /// From the mesh's units to the world.
    pub model: Mat4,
    /// Its colour.
    pub color: [f32; 3],
}

/// A mesh on the card: its vertex array, buffer and vertex count.
struct OnCard {
    mesh: Arc<Mesh>,
    array: glow::VertexArray,
    buffer: glow::Buffer,
    vertices: i32,
}

/// What the card holds between frames: the program and the uploaded meshes.
#[derive(Default)]
pub struct Card {
    program: Option<glow::Program>,
    meshes: HashMap<usize, OnCard>,
    /// The program would not build: nothing is drawn (said once on stderr).
    broken: bool,
}

impl std::fmt::Debug for Card {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Card").field("meshes", &self.meshes.len()).field("broken", &self.broken).finish()
    }
}

/// The callback that draws `items` seen through `view_projection` in `rect`.
pub fn callback(
    rect: egui::Rect,
    view_projection: Mat4,
    light: Vec3,
    items: Vec<Item>,
    card: Arc<Mutex<Card>>,
) -> egui::PaintCallback {
    let draw = egui_glow::CallbackFn::new(move |_info, painter| {
        if let Ok(mut card) = card.lock() {
            card.draw(painter.gl(), view_projection, light, &items);
        }
    });
    egui::PaintCallback { rect, callback: Arc::new(draw) }
}

const VERTEX: &str = r"
#if NEW_SHADER_INTERFACE
#define I in
#define V out
#else
#define I attribute
#define V varying
#endif
uniform mat4 u_mvp;
uniform mat3 u_normal;
uniform vec3 u_color;
uniform vec3 u_light;
I vec3 a_position;
I vec3 a_normal;
V vec3 v_color;
void main() {
    vec3 n = normalize(u_normal * a_normal);
    float light = 0.35 + 0.65 * max(dot(n, u_light), 0.0);
    v_color = u_color * light;
    gl_Position = u_mvp * vec4(a_position, 1.0);
}
";

const FRAGMENT: &str = r"
#if NEW_SHADER_INTERFACE
#define V in
out vec4 out_color;
#else
#define V varying
#define out_color gl_FragColor
#endif
V vec3 v_color;
void main() {
    out_color = vec4(v_color, 1.0);
}
";

impl Card {
    fn draw(&mut self, gl: &glow::Context, view_projection: Mat4, light: Vec3, items: &[Item]) {
        if self.broken {
            return;
        }
        let Some(program) = self.program.or_else(|| self.build(gl)) else { return };
        // Meshes no frame draws any more (only the card holds them) are let go.
        let gone: Vec<usize> =
            self.meshes.iter().filter(|(_, on)| Arc::strong_count(&on.mesh) == 1).map(|(key, _)| *key).collect();
        for key in gone {
            if let Some(on) = self.meshes.remove(&key) {
                unsafe {
                    gl.delete_vertex_array(on.array);
                    gl.delete_buffer(on.buffer);
                }
            }
        }
        unsafe {
            gl.use_program(Some(program));
            gl.enable(glow::DEPTH_TEST);
            gl.depth_func(glow::LEQUAL);
            gl.depth_mask(true);
            // Within the view only: the painter's scissor is the view's clip.
            gl.clear_depth_f32(1.0);
            gl.clear(glow::DEPTH_BUFFER_BIT);
            let location = |name: &str| gl.get_uniform_location(program, name);
            gl.uniform_3_f32_slice(location("u_light").as_ref(), &light.normalize_or_zero().to_array());
            for item in items {
                let Some(on) = self.upload(gl, program, &item.mesh) else { continue };
                let mvp = view_projection * item.model;
                let normal = Mat3::from_mat4(item.model).inverse().transpose();
                gl.uniform_matrix_4_f32_slice(location("u_mvp").as_ref(), false, &mvp.to_cols_array());
                gl.uniform_matrix_3_f32_slice(location("u_normal").as_ref(), false, &normal.to_cols_array());
                gl.uniform_3_f32_slice(location("u_color").as_ref(), &item.color);
                gl.bind_vertex_array(Some(on.0));
                gl.draw_arrays(glow::TRIANGLES, 0, on.1);
            }
            gl.bind_vertex_array(None);
            gl.disable(glow::DEPTH_TEST);
        }
    }

    /// The program, built once; none (and never tried again) if it will not build.
    fn build(&mut self, gl: &glow::Context) -> Option<glow::Program> {
        let version = egui_glow::ShaderVersion::get(gl);
        let header = format!(
            "{}#define NEW_SHADER_INTERFACE {}\n{}",
            version.version_declaration(),
            i32::from(version.is_new_shader_interface()),
            if version.is_embedded() { "precision mediump float;\n" } else { "" }
        );
        let built = unsafe {
            let program = gl.create_program().ok()?;
            let mut shaders = Vec::new();
            for (kind, source) in [(glow::VERTEX_SHADER, VERTEX), (glow::FRAGMENT_SHADER, FRAGMENT)] {
                let shader = gl.create_shader(kind).ok()?;
                gl.shader_source(shader, &format!("{header}{source}"));
                gl.compile_shader(shader);
                if !gl.get_shader_compile_status(shader) {
                    eprintln!("3D view: a mesh shader would not compile: {}", gl.get_shader_info_log(shader));
                    return None;
                }
                gl.attach_shader(program, shader);
                shaders.push(shader);
            }
            gl.bind_attrib_location(program, 0, "a_position");
            gl.bind_attrib_location(program, 1, "a_normal");
            gl.link_program(program);
            for shader in shaders {
                gl.detach_shader(program, shader);
                gl.delete_shader(shader);
            }
            if !gl.get_program_link_status(program) {
                eprintln!("3D view: the mesh program would not link: {}", gl.get_program_info_log(program));
                return None;
            }
            Some(program)
        };
        self.broken = built.is_none();
        self.program = built;
        built
    }

    /// The mesh on the card (uploaded the first time it is drawn).
    fn upload(
        &mut self,
        gl: &glow::Context,
        _program: glow::Program,
        mesh: &Arc<Mesh>,
    ) -> Option<(glow::VertexArray, i32)> {
        let key = Arc::as_ptr(mesh) as usize;
        if let Some(on) = self.meshes.get(&key) {
            return Some((on.array, on.vertices));
        }
        // Three corners a triangle, each its position and the triangle's normal.
        let mut bytes = Vec::with_capacity(mesh.triangles.len() * 3 * 6 * 4);
        for (corners, normal) in mesh.triangles.iter().zip(&mesh.normals) {
            for &corner in corners {
                let position = mesh.positions.get(corner as usize).copied().unwrap_or(Vec3::ZERO);
                for value in position.to_array().into_iter().chain(normal.to_array()) {
                    bytes.extend_from_slice(&value.to_ne_bytes());
                }
            }
        }
        let vertices = i32::try_from(mesh.triangles.len() * 3).ok()?;
        let on = unsafe {
            let array = gl.create_vertex_array().ok()?;
            let buffer = gl.create_buffer().ok()?;
            gl.bind_vertex_array(Some(array));
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(buffer));
            gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, &bytes, glow::STATIC_DRAW);
            gl.vertex_attrib_pointer_f32(0, 3, glow::FLOAT, false, 24, 0);
            gl.enable_vertex_attrib_array(0);
            gl.vertex_attrib_pointer_f32(1, 3, glow::FLOAT, false, 24, 12);
            gl.enable_vertex_attrib_array(1);
            gl.bind_vertex_array(None);
            gl.bind_buffer(glow::ARRAY_BUFFER, None);
            OnCard { mesh: Arc::clone(mesh), array, buffer, vertices }
        };
        let drawn = (on.array, on.vertices);
        self.meshes.insert(key, on);
        Some(drawn)
    }
}
