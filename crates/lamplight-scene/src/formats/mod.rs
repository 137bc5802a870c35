//! Scene file formats: the native TOML format ([`native`]).

pub mod native;
