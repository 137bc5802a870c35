//! Every integration test of this crate, as modules of one test binary: each
//! binary links the whole dependency graph, so one binary instead of one per
//! file saves most of `cargo test`'s link time and the generic code compiled
//! again for each (issue 24, the test suite's time). A new test file is one
//! more `mod` line here; `cargo test -p lamplight-scene --test all NAME` runs one.

mod common;

mod alpha_blend;
mod animation;
mod anisotropic;
mod bare_mesh;
mod blend;
mod business_card;
mod cameras;
mod convert;
mod denoise;
mod environment;
mod errors;
mod explain;
mod fuzz_props;
mod gltf;
mod gltf_animation;
mod gltf_animation_choice;
mod gltf_animation_convert;
mod gltf_animation_scene;
mod golden;
mod lights;
mod mesh_lights;
mod mitsuba;
mod mitsuba_amplification;
mod mitsuba_bsdfs;
mod mitsuba_plugins;
mod mitsuba_principled;
mod mitsuba_rough_textures;
mod mitsuba_sdfgrid;
mod mitsuba_sensors;
mod mitsuba_textures;
mod mitsuba_wrappers;
mod motion_blur;
mod native;
mod obj;
mod path_convergence;
mod path_footprint;
mod ply;
mod real_files;
mod reference;
mod scaled;
mod special_files;
mod textures;
mod transmission;
mod vertex_attributes;
