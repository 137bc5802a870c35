//! Property tests of the scene parser and builder on hostile input: random
//! text, and random mutations (deleted ranges, inserted fragments, replaced
//! bytes) of the example scene files. Whatever the input, loading returns `Ok` or
//! one `LoadError` and never panics. The seed is fixed, so the suite is
//! deterministic; `fuzz/` runs the same check open-ended with libFuzzer.

use std::path::Path;

use lamplight_scene::instantiate::SceneFile;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

const EXAMPLES: [&str; 4] = [
    include_str!("../../../examples/luxo.toml"),
    include_str!("../../../examples/business-card.toml"),
    include_str!("../../../examples/spheres.toml"),
    include_str!("../../../examples/turntable.toml"),
];

/// Fragments a mutation may insert: TOML syntax, keys and values that matter.
const FRAGMENTS: &[&str] = &[
    "[",
    "]",
    "{",
    "}",
    "=",
    ",",
    "\"",
    "\n",
    "#",
    "nan",
    "inf",
    "-inf",
    "-1",
    "0",
    "1e308",
    "4294967296",
    "[[objects]]\n",
    "type = \"instance\"\n",
    "of = \"d\"\n",
    "[definitions.d]\ntype = \"instance\"\nof = \"d\"\n",
    "type = \"implicit\"\n",
    "expression = \"((((x\"\n",
    "scale = 0\n",
    "matrix = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]\n",
    "rotate = { axis = [0,0,0], degrees = 90 }\n",
    "file = \".\"\n",
    "file = \"missing.obj\"\n",
    "children = [",
    "radius = -1\n",
    "material = \"none\"\n",
    "[render]\nwidth = 0\n",
    "type = \"torus\"\n",
    "type = \"box\"\n",
    "\u{feff}",
    "é",
    "[animation]\nframes = [1, 3]\n",
    "animate.translate = { frames = [1, 2], values = [[0, 0, 0], [1e308, 0, 0]] }\n",
    "animate.rotate = { seconds = [0, 1], values = [[0, 0, 0], { quaternion = [0, 1, 0, 0] }], interpolation = \"cubicspline\", out_tangents = [[1e308, 0, 0, 0], [0, 0, 0, 0]] }\n",
    "interpolation = \"step\"\n",
];

/// Parses and builds `text`; a panic fails the property.
fn load(text: &str) {
    if let Ok(file) = SceneFile::parse(Path::new("fuzz.toml"), text) {
        if file.settings().is_ok() {
            let _ = file.build();
            // An animated scene: a frame between keys and one past the last too.
            if file.description.animation.is_some() {
                let _ = file.build_frame(Some(2));
                let _ = file.build_frame(Some(1_000));
            }
        }
    }
}

#[derive(Debug, Clone)]
enum Edit {
    Delete(usize, usize),
    Insert(usize, usize),
    Replace(usize, u8),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), 0usize..64).prop_map(|(at, len)| Edit::Delete(at, len)),
        (any::<usize>(), 0..FRAGMENTS.len()).prop_map(|(at, f)| Edit::Insert(at, f)),
        (any::<usize>(), any::<u8>()).prop_map(|(at, b)| Edit::Replace(at, b)),
    ]
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for e in edits {
        let n = bytes.len().max(1);
        match *e {
            Edit::Delete(at, len) => {
                let at = at % n;
                let end = (at + len).min(bytes.len());
                bytes.drain(at.min(end)..end);
            }
            Edit::Insert(at, f) => {
                let at = (at % n).min(bytes.len());
                bytes.splice(at..at, FRAGMENTS[f].bytes());
            }
            Edit::Replace(at, b) => {
                if !bytes.is_empty() {
                    let at = at % bytes.len();
                    bytes[at] = b;
                }
            }
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

fn config(cases: u32, seed: u64) -> Config {
    Config { cases, rng_seed: RngSeed::Fixed(seed), failure_persistence: None, ..Config::default() }
}

proptest! {
    #![proptest_config(config(256, 0x5ce7e))]

    #[test]
    fn mutated_examples_never_panic(which in 0..EXAMPLES.len(), edits in prop::collection::vec(edit(), 1..8)) {
        load(&apply(EXAMPLES[which], &edits));
    }
}

proptest! {
    #![proptest_config(config(512, 0xf11e))]

    #[test]
    fn random_text_never_panics(text in "(\\PC|\\n|[\\[\\]{}=,\"#.0-9a-z_ -]){0,200}") {
        load(&text);
    }

    #[test]
    fn random_node_tables_never_panic(kind in 0..FRAGMENTS.len(), body in prop::collection::vec(0..FRAGMENTS.len(), 0..12)) {
        let mut text = String::from("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n[[objects]]\n");
        text += FRAGMENTS[kind];
        for f in body {
            text += FRAGMENTS[f];
        }
        load(&text);
    }
}

#[test]
fn the_examples_themselves_load() {
    for text in EXAMPLES {
        let file = SceneFile::parse(Path::new("e.toml"), text).unwrap();
        file.build().unwrap();
    }
}
