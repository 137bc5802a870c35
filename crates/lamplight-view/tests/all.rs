//! Every integration test of this crate, as modules of one test binary: each
//! binary links the whole dependency graph, so one binary instead of one per
//! file saves most of `cargo test`'s link time and the generic code compiled
//! again for each (issue 24, the test suite's time). A new test file is one
//! more `mod` line here; `cargo test -p lamplight-view --test all NAME` runs one.

mod doors;
mod server;
mod storm;
mod timeline;
mod warnings;
