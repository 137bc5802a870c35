//! # lamplight-scene
//!
//! Everything between the outside world and `lamplight-core`. A scene goes
//! through three stages, each a folder of its own (Mitsuba's parse, describe and
//! instantiate):
//!
//! 1. **Parse** ([`formats`], [`import`]): a file in its own syntax (the native
//!    TOML format, Mitsuba 3 XML, OBJ/PLY/glTF meshes) or a Python dict becomes
//!    located tables and meshes. Nothing is interpreted yet.
//! 2. **Describe** ([`description`]): plain data, a tree of nodes `{type, name,
//!    transform, children, params}` in which every key and value carries its
//!    source location, so that any later error can name the file, line and
//!    column, or the key path.
//! 3. **Instantiate** ([`instantiate`]): each node's kind is looked up in the
//!    [`registry`], reads its parameters from its own table, and becomes a core
//!    shape, material, light or camera; the result is a core
//!    [`lamplight_core::Scene`] ready to render.
//!
//! Around them: the [`request`] layer shared by the CLI and Python (which scene,
//! settings precedence, limits), the built-in scenes by name ([`builtin`]), the
//! image writers ([`image_io`]), the denoiser ([`denoise`]), what a file holds ([`info`]), NumPy `.npy`
//! arrays ([`npy`]), the checks every input file passes ([`input`]), the memory budget every reader draws on ([`memory`]) and the
//! atomic writes every written file goes through ([`atomic`]).
#![deny(missing_docs)]

pub mod atomic;
pub mod builtin;
pub mod convert;
pub mod denoise;
pub mod description;
pub mod enclosed;
pub mod env_map;
mod error;
pub mod explain;
pub mod expr;
pub mod exr_layers;
mod exr_zip;
pub mod formats;
pub mod image_io;
pub mod import;
pub mod info;
pub mod input;
pub mod instantiate;
pub mod memory;
pub mod npy;
mod png_write;
pub mod registry;
pub mod request;
pub mod texture_files;

pub use error::{LoadError, Location};
