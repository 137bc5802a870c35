//! Denoising with Intel Open Image Denoise (OIDN), the denoiser of Cycles,
//! Arnold and Blender's compositor: its `RT` filter, HDR, on linear radiance,
//! guided by the feature layers ([`lamplight_core::render_features`]).
//!
//! **Why the library is loaded at run time.** OIDN is a C++ library of some
//! 60 MB with its trained weights. A fresh machine has it only from a package
//! registry: the PyPI wheel `pyoidn` ships the whole 2.x runtime. The crates.io
//! crate `oidn` links an OIDN already installed (and its `bundled` feature
//! downloads one at build time), so linking would make every build of lamplight
//! need OIDN, or a cargo feature that the README's first command would not
//! have. Opening the library (`dlopen`, through `libloading`) only when a
//! render asks for `--denoise` keeps `cargo install` free of it and lets one
//! binary denoise wherever the library is present; only OIDN's stable C API is
//! used (`denoise/oidn.rs`). Without the library, `--denoise` stops before rendering
//! with one line saying how to get it ([`Denoiser::load`]).
//!
//! **Where the library is looked for**, in order:
//! 1. `LAMPLIGHT_OIDN` ([`ENV_VAR`]): the library file or its folder. When
//!    set it is the only place looked at, so a wrong value is an error, not a
//!    silent fallback.
//! 2. The folders the front end knows of (Python's: the `pyoidn` package it
//!    imports from), then the `pyoidn` package of the Python of the active
//!    virtual environment (`$VIRTUAL_ENV`) or of `python3` on `PATH`, asked
//!    where it is (`importlib.util.find_spec`, which imports nothing).
//! 3. The system's loader paths (`LD_LIBRARY_PATH`, `/usr/lib`, ...), as an
//!    installed OIDN is found.
//!
//! A library, once loaded, stays for the process's life and is shared by
//! every later [`Denoiser::load`] that finds it at the same path, with the
//! device and filter it keeps between calls (`denoise/oidn.rs`: made once,
//! reused while the image's size is the same, one call at a time).
//!
//! **What is filtered.** The image less its `emitted` part, when the render
//! gives one ([`lamplight_core::Features::emitted`]: emitters and sky seen
//! directly, which have no Monte Carlo noise), and that part is added back
//! after; the HDR filter never sees a light's edge, where it moved pixels of
//! radiance 18 by up to 2 (`BENCHMARKS.md`, "Denoising"). The filter runs in
//! HDR mode with its own exposure (`inputScale` unset: OIDN scales by the
//! image's own average), and without `cleanAux`: the features are noise-free
//! on Lambertian surfaces but estimated (2 samples) on others, and OIDN's
//! manual warns that noisy features with `cleanAux` leave their noise in the
//! output.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

use lamplight_core::film::Image;

mod exr_input;
mod oidn;

pub use exr_input::{read_denoise_input, DenoiseInput};

/// The variable naming the library or its folder.
pub const ENV_VAR: &str = "LAMPLIGHT_OIDN";

/// The library's file name: 2.x, the major version whose API `denoise/oidn.rs` uses.
#[cfg(target_os = "macos")]
pub const LIBRARY: &str = "libOpenImageDenoise.2.dylib";
/// The library's file name: 2.x, the major version whose API `denoise/oidn.rs` uses.
#[cfg(windows)]
pub const LIBRARY: &str = "OpenImageDenoise.dll";
/// The library's file name: 2.x, the major version whose API `denoise/oidn.rs` uses.
#[cfg(not(any(target_os = "macos", windows)))]
pub const LIBRARY: &str = "libOpenImageDenoise.so.2";

/// Where the `pyoidn` wheel keeps the library, inside its package folder.
const PYOIDN_LIB: &str = "oidn/lib";

/// Why denoising cannot be done: one line for the user.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DenoiseError(pub String);

impl std::fmt::Display for DenoiseError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for DenoiseError {}

/// The message for a machine without the library.
pub fn missing_message() -> String {
    format!(
        "denoising needs Intel Open Image Denoise 2.x, which was not found: install it with `pip install pyoidn` \
         (into the python3 on PATH or the active virtual environment), or set {ENV_VAR} to {LIBRARY} or its folder"
    )
}

/// Open Image Denoise, loaded.
pub struct Denoiser {
    oidn: Arc<oidn::Oidn>,
}

/// Every library this process has loaded, by the path it was loaded from (see the module doc).
static LOADED: Mutex<Vec<Arc<oidn::Oidn>>> = Mutex::new(Vec::new());

/// The library at `path`: the one loaded before from there, else loaded now.
fn open(path: &Path) -> Result<Denoiser, String> {
    let mut loaded = LOADED.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some(oidn) = loaded.iter().find(|o| o.path == path) {
        return Ok(Denoiser { oidn: Arc::clone(oidn) });
    }
    let oidn = Arc::new(oidn::Oidn::load(path)?);
    loaded.push(Arc::clone(&oidn));
    Ok(Denoiser { oidn })
}

impl std::fmt::Debug for Denoiser {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Denoiser({})", self.oidn.path.display())
    }
}

impl Denoiser {
    /// Finds and loads the library (see the module doc for where), with the
    /// front end's own candidate folders `hints`; [`missing_message`] when it
    /// is nowhere.
    pub fn load(hints: &[PathBuf]) -> Result<Denoiser, DenoiseError> {
        if let Some(value) = std::env::var_os(ENV_VAR).filter(|v| !v.is_empty()) {
            let given = PathBuf::from(&value);
            let path = if given.is_dir() { given.join(LIBRARY) } else { given };
            // A path, never a name for the loader to search: `lib.so` means ./lib.so.
            let path = std::path::absolute(&path).unwrap_or(path);
            return open(&path)
                .map_err(|e| DenoiseError(format!("{ENV_VAR}={}: cannot load Open Image Denoise: {e}", Path::new(&value).display())));
        }
        // The Pythons are asked (a process each) only when the hints fail.
        let asked = std::iter::once(()).flat_map(|()| python_pyoidn_folders());
        for folder in hints.iter().cloned().chain(asked) {
            let path = folder.join(LIBRARY);
            if path.is_file() {
                if let Ok(denoiser) = open(&path) {
                    return Ok(denoiser);
                }
            }
        }
        open(Path::new(LIBRARY)).map_err(|_| DenoiseError(missing_message()))
    }

    /// Where the library was loaded from.
    pub fn library_path(&self) -> &Path {
        &self.oidn.path
    }

    /// `color` denoised by the HDR `RT` filter, guided by `albedo` and `normal`
    /// (each in its range: albedo `[0, 1]`, normal `[-1, 1]`) when given, on
    /// `threads` threads (0: all cores). With `emitted`, the part of `color`
    /// that has no noise (emitters and sky seen directly), only `color -
    /// emitted` is filtered and `emitted` added back (see the module doc).
    /// Negative and non-finite values, which a filter with negative lobes can
    /// leave and the HDR filter does not take, are read as 0.
    pub fn denoise(&self, color: &Image, guides: Guides<'_>, threads: usize) -> Result<Image, DenoiseError> {
        let size = (color.width, color.height);
        let Guides { albedo, normal, emitted } = guides;
        for (name, image) in [("albedo", albedo), ("normal", normal), ("emitted", emitted)] {
            if let Some(image) = image.filter(|i| (i.width, i.height) != size) {
                return Err(DenoiseError(format!("the {name} layer is {}x{}, the image {}x{}", image.width, image.height, size.0, size.1)));
            }
        }
        let plain = |v: f32| if v.is_finite() && v > 0.0 { v } else { 0.0 };
        let color = color.pixels.as_flattened();
        let emitted: Option<Vec<f32>> = emitted.map(|e| e.pixels.as_flattened().iter().map(|&v| plain(v)).collect());
        let beauty: Vec<f32> = match &emitted {
            Some(e) => color.iter().zip(e).map(|(&c, &e)| plain(plain(c) - e)).collect(),
            None => color.iter().map(|&v| plain(v)).collect(),
        };
        fn flat(image: Option<&Image>) -> Option<&[f32]> {
            image.map(|i| i.pixels.as_flattened())
        }
        let dims = (size.0 as usize, size.1 as usize);
        let mut out = self
            .oidn
            .filter_rt(dims, &beauty, flat(albedo), flat(normal), threads)
            .map_err(|e| DenoiseError(format!("Open Image Denoise ({}): {e}", self.oidn.path.display())))?;
        if let Some(e) = &emitted {
            out.iter_mut().zip(e).for_each(|(o, &e)| *o = plain(*o) + e);
        }
        let pixels = out.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        Ok(Image { width: size.0, height: size.1, pixels })
    }
}

/// What guides [`Denoiser::denoise`] beside the image, each of its size when given.
#[derive(Clone, Copy, Debug, Default)]
pub struct Guides<'a> {
    /// The albedo feature, in `[0, 1]`.
    pub albedo: Option<&'a Image>,
    /// The normal feature, in `[-1, 1]`.
    pub normal: Option<&'a Image>,
    /// The noise-free part of the image that is not filtered but added back
    /// ([`lamplight_core::Features::emitted`]).
    pub emitted: Option<&'a Image>,
}

impl<'a> Guides<'a> {
    /// All three from a render's feature pass.
    pub fn of(features: &'a lamplight_core::Features) -> Guides<'a> {
        Guides { albedo: Some(&features.albedo), normal: Some(&features.normal), emitted: Some(&features.emitted) }
    }
}

/// The `pyoidn` library folders of the Pythons at hand: the active virtual
/// environment's, then `python3` on `PATH`. Each is asked where the package is
/// without importing it; a Python that is missing or lacks it adds nothing.
fn python_pyoidn_folders() -> Vec<PathBuf> {
    let mut pythons: Vec<PathBuf> = Vec::new();
    if let Some(venv) = std::env::var_os("VIRTUAL_ENV") {
        pythons.push(PathBuf::from(venv).join("bin").join("python"));
    }
    pythons.push(PathBuf::from("python3"));
    let script = "import importlib.util as u\ns = u.find_spec('pyoidn')\nprint(s.submodule_search_locations[0] if s and s.submodule_search_locations else '')";
    pythons
        .iter()
        .filter_map(|python| {
            let out = std::process::Command::new(python).args(["-c", script]).stderr(std::process::Stdio::null()).output().ok()?;
            let folder = String::from_utf8(out.stdout).ok()?.trim().to_string();
            (out.status.success() && !folder.is_empty()).then(|| Path::new(&folder).join(PYOIDN_LIB))
        })
        .collect()
}

/// The denoiser for the test `test`, which needs it: `None`, after a line
/// saying that the test is skipped and why, on a machine without the library;
/// but under CI (`CI` set), where `scripts/test.sh` installs it, a missing
/// library fails the test instead of skipping it.
pub fn for_test(test: &str) -> Option<Denoiser> {
    match Denoiser::load(&[]) {
        Ok(denoiser) => Some(denoiser),
        Err(e) if std::env::var_os("CI").is_some() => {
            panic!("{test}: CI must denoise (scripts/test.sh installs pyoidn and sets {ENV_VAR}): {e}")
        }
        Err(e) => {
            eprintln!("{test}: skipped: {e}");
            None
        }
    }
}

/// The library folder inside the `pyoidn` package folder `package`, for front
/// ends that find the package themselves (Python).
pub fn pyoidn_library_folder(package: &Path) -> PathBuf {
    package.join(PYOIDN_LIB)
}
