//! The part of Open Image Denoise's C API (`OpenImageDenoise/oidn.h`, 2.x)
//! that lamplight calls, loaded from the shared library at run time.
//!
//! Only functions of the stable 2.x API are resolved: `oidnNewDevice`,
//! `oidnSetDeviceInt`, `oidnCommitDevice`, `oidnGetDeviceError`,
//! `oidnNewFilter`, `oidnSetSharedFilterImage`, `oidnSetFilterBool`,
//! `oidnCommitFilter`, `oidnExecuteFilter` and the two releases. Images are
//! shared with the library in host memory (`oidnSetSharedFilterImage`, which
//! the CPU device reads in place), so no buffer is copied.

use std::ffi::{c_char, c_int, c_void, CStr};
use std::path::{Path, PathBuf};

use libloading::Library;

type Device = *mut c_void;
type Filter = *mut c_void;

/// `OIDN_DEVICE_TYPE_CPU`: the device every build of the library has, and the
/// one that reads host memory shared with it.
const DEVICE_TYPE_CPU: c_int = 1;
/// `OIDN_FORMAT_FLOAT3`: three 32-bit floats per pixel.
const FORMAT_FLOAT3: c_int = 3;
/// `OIDN_ERROR_NONE`.
const ERROR_NONE: c_int = 0;

/// The library's entry points, resolved once; `lib` keeps them mapped.
pub(super) struct Oidn {
    new_device: unsafe extern "C" fn(c_int) -> Device,
    set_device_int: unsafe extern "C" fn(Device, *const c_char, c_int),
    commit_device: unsafe extern "C" fn(Device),
    get_device_error: unsafe extern "C" fn(Device, *mut *const c_char) -> c_int,
    release_device: unsafe extern "C" fn(Device),
    new_filter: unsafe extern "C" fn(Device, *const c_char) -> Filter,
    set_shared_filter_image: unsafe extern "C" fn(Filter, *const c_char, *mut c_void, c_int, usize, usize, usize, usize, usize),
    set_filter_bool: unsafe extern "C" fn(Filter, *const c_char, bool),
    commit_filter: unsafe extern "C" fn(Filter),
    execute_filter: unsafe extern "C" fn(Filter),
    release_filter: unsafe extern "C" fn(Filter),
    /// Where it was loaded from.
    pub(super) path: PathBuf,
    _lib: Library,
}

impl Oidn {
    /// Loads the library at `path` (a file name alone is searched for as the
    /// system's loader does) and resolves every entry point, or says why not.
    pub(super) fn load(path: &Path) -> Result<Oidn, String> {
        // SAFETY: loading runs the library's initializers; Open Image Denoise's
        // only register its devices. The symbols are typed as oidn.h declares them.
        unsafe {
            let lib = Library::new(path).map_err(|e| e.to_string())?;
            macro_rules! symbol {
                ($name:literal) => {
                    *lib.get(concat!($name, "\0").as_bytes()).map_err(|e| format!("{}: {e}", path.display()))?
                };
            }
            Ok(Oidn {
                new_device: symbol!("oidnNewDevice"),
                set_device_int: symbol!("oidnSetDeviceInt"),
                commit_device: symbol!("oidnCommitDevice"),
                get_device_error: symbol!("oidnGetDeviceError"),
                release_device: symbol!("oidnReleaseDevice"),
                new_filter: symbol!("oidnNewFilter"),
                set_shared_filter_image: symbol!("oidnSetSharedFilterImage"),
                set_filter_bool: symbol!("oidnSetFilterBool"),
                commit_filter: symbol!("oidnCommitFilter"),
                execute_filter: symbol!("oidnExecuteFilter"),
                release_filter: symbol!("oidnReleaseFilter"),
                path: path.to_path_buf(),
                _lib: lib,
            })
        }
    }

    /// Runs the `RT` filter (HDR) on `color`, `width x height` RGB triples,
    /// guided by `albedo` and `normal` of the same size when given; on `threads`
    /// worker threads (0: the library's choice, every core).
    pub(super) fn filter_rt(
        &self,
        (width, height): (usize, usize),
        color: &[f32],
        albedo: Option<&[f32]>,
        normal: Option<&[f32]>,
        threads: usize,
    ) -> Result<Vec<f32>, String> {
        let floats = width * height * 3;
        for image in [Some(color), albedo, normal].into_iter().flatten() {
            assert_eq!(image.len(), floats, "image size checked by the caller");
        }
        let mut output = vec![0.0f32; floats];
        // SAFETY: every image is `width * height` FLOAT3 pixels, tightly packed,
        // and outlives the filter's execution; the library reads the inputs only
        // and writes the output. Device and filter are released on every path.
        unsafe {
            let device = (self.new_device)(DEVICE_TYPE_CPU);
            if device.is_null() {
                return Err(self.error(std::ptr::null_mut()).unwrap_or_else(|| "cannot create a CPU device".into()));
            }
            let result = (|| {
                if threads > 0 {
                    (self.set_device_int)(device, c"numThreads".as_ptr(), threads.min(c_int::MAX as usize) as c_int);
                }
                (self.commit_device)(device);
                self.check(device)?;
                let filter = (self.new_filter)(device, c"RT".as_ptr());
                if filter.is_null() {
                    return Err(self.error(device).unwrap_or_else(|| "cannot create the RT filter".into()));
                }
                let image = |name: &CStr, data: *mut f32| {
                    (self.set_shared_filter_image)(filter, name.as_ptr(), data.cast(), FORMAT_FLOAT3, width, height, 0, 0, 0)
                };
                image(c"color", color.as_ptr().cast_mut());
                if let Some(albedo) = albedo {
                    image(c"albedo", albedo.as_ptr().cast_mut());
                }
                if let Some(normal) = normal {
                    image(c"normal", normal.as_ptr().cast_mut());
                }
                image(c"output", output.as_mut_ptr());
                (self.set_filter_bool)(filter, c"hdr".as_ptr(), true);
                (self.commit_filter)(filter);
                let committed = self.check(device);
                if committed.is_ok() {
                    (self.execute_filter)(filter);
                }
                (self.release_filter)(filter);
                committed.and_then(|()| self.check(device))
            })();
            (self.release_device)(device);
            result?;
        }
        Ok(output)
    }

    /// The device's first error since the last check, if any.
    unsafe fn error(&self, device: Device) -> Option<String> {
        let mut message: *const c_char = std::ptr::null();
        let code = (self.get_device_error)(device, &mut message);
        (code != ERROR_NONE).then(|| {
            if message.is_null() {
                format!("error {code}")
            } else {
                CStr::from_ptr(message).to_string_lossy().into_owned()
            }
        })
    }

    unsafe fn check(&self, device: Device) -> Result<(), String> {
        self.error(device).map_or(Ok(()), Err)
    }
}
