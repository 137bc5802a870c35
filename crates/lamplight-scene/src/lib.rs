//! # lamplight-scene
//!
//! Everything between the outside world and `lamplight-core`: the built-in scenes
//! by name ([`builtin`]), the image writers ([`image_io`]), the scene file format
//! ([`description`] types, [`formats::native`] TOML parser, the [`registry`] of
//! kinds, [`build`] to a core scene, the [`request`] layer shared by the CLI and
//! Python), the mesh importers ([`import`]), what a file holds ([`info`]), NumPy `.npy` arrays ([`npy`]), the
//! checks every input file passes ([`input`]) and the atomic writes every written
//! file goes through ([`atomic`]).
#![deny(missing_docs)]

pub mod atomic;
pub mod build;
pub mod builtin;
pub mod convert;
pub mod description;
pub mod env_map;
mod error;
pub mod explain;
pub mod expr;
pub mod exr_layers;
pub mod formats;
pub mod image_io;
pub mod import;
pub mod info;
pub mod input;
pub mod npy;
pub mod registry;
pub mod request;
pub mod texture_files;

pub use error::{LoadError, Location};
