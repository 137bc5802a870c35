//! # lamplight-scene
//!
//! Everything between the outside world and `lamplight-core`: the built-in scenes
//! by name ([`builtin`]), and the image writers ([`image_io`]). Scene files and
//! mesh formats join here as modules of their own.
#![deny(missing_docs)]

pub mod builtin;
mod error;
pub mod image_io;
pub mod import;

pub use error::{LoadError, Location};
