//! Every integration test of this crate, as modules of one test binary: each
//! binary links the whole dependency graph, so one binary instead of one per
//! file saves most of `cargo test`'s link time and the generic code compiled
//! again for each (issue 24, the test suite's time). A new test file is one
//! more `mod` line here; `cargo test -p lamplight-cli --test all NAME` runs one.

mod budgets;
mod cli;
mod denoise;
mod explain;
mod frames;
mod gltf_frames;
mod hardening;
mod info;
mod lighting;
mod meshes;
mod raycast;
mod video;
mod view;
