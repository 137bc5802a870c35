//! The part of Open Image Denoise's C API (`OpenImageDenoise/oidn.h`, 2.x)
//! that lamplight calls, loaded from the shared library at run time, and the
//! device and filter it keeps between calls.
//!
//! Only functions of the stable 2.x API are resolved: `oidnNewDevice`,
//! `oidnSetDeviceInt`, `oidnCommitDevice`, `oidnGetDeviceError`,
//! `oidnNewFilter`, `oidnSetSharedFilterImage`, `oidnSetFilterBool`,
//! `oidnCommitFilter`, `oidnExecuteFilter` and the two releases.
//!
//! **One device and one filter per process, reused.** Making a device (its
//! thread pool, the CPU's kernels) and committing a filter (the network,
//! its weights laid out, its scratch memory) cost more than filtering a small
//! image, and OIDN's manual says not to do either per frame; the viewer
//! denoises every progressive frame, and Python may call `denoise` in a loop.
//! So the first call makes them and later calls reuse them: the device while
//! the thread count asked for is the same, a filter while the image's size
//! and guides (albedo, normal) are. A filter reads and writes four buffers of
//! its own (`oidnSetSharedFilterImage` on host memory, which the CPU device
//! uses in place), set once at its commit; a call copies its images into them,
//! executes, and copies the output out, so no commit happens between calls of
//! one size. [`KEPT_FILTERS`] filters are kept, the most recently used, as the
//! viewer's stages come in three sizes (preview, half, full); OIDN lets the
//! filters of one device share their scratch memory. An error releases the
//! device and its filters, so the next call starts afresh.
//!
//! **Threads.** OIDN's API is thread-safe, but it serializes the operations of
//! one device, and the one kept filter's buffers are written by each call, so
//! a [`Mutex`] around the device and filter makes every call, from set-up to
//! the copied output, exclusive: concurrent callers (Python threads, a Dask
//! client, the viewer beside a render) wait their turn. One filter execution
//! uses every core of the device already, so two at once would not be faster.

use std::ffi::{c_char, c_int, c_void, CStr};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};

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

/// Filters kept, one per image size and guides: the viewer's three stage sizes.
pub(super) const KEPT_FILTERS: usize = 3;

/// The library's entry points, resolved once; `lib` keeps them mapped.
pub(super) struct Oidn {
    api: Api,
    /// The device and filter kept between calls (see the module doc).
    kept: Mutex<Option<Kept>>,
    /// Where it was loaded from.
    pub(super) path: PathBuf,
    _lib: Library,
}

struct Api {
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
}

/// A committed device, with the thread count it was made for, and its
/// filters, the most recently used first.
struct Kept {
    device: Device,
    threads: usize,
    filters: Vec<KeptFilter>,
}

/// A committed `RT` filter and the buffers it was committed with.
struct KeptFilter {
    filter: Filter,
    /// `(width, height, albedo given, normal given)`.
    shape: (usize, usize, bool, bool),
    color: Vec<f32>,
    albedo: Vec<f32>,
    normal: Vec<f32>,
    output: Vec<f32>,
}

// SAFETY: OIDN's objects may be used from any thread (its API is thread-safe);
// `Kept` is only reached through the `Mutex` in `Oidn`, so one thread at a time
// uses it, and the buffers it owns never move while the filter holds them
// (they are neither resized nor dropped before the filter is released).
unsafe impl Send for Kept {}

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
            let api = Api {
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
            };
            Ok(Oidn { api, kept: Mutex::new(None), path: path.to_path_buf(), _lib: lib })
        }
    }

    /// Runs the `RT` filter (HDR) on `color`, `width x height` RGB triples,
    /// guided by `albedo` and `normal` of the same size when given; on `threads`
    /// worker threads (0: the library's choice, every core). Reuses the kept
    /// device and filter when they fit (see the module doc).
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
        // A panic elsewhere while holding the lock leaves nothing half-made
        // that matters: the kept objects are dropped and made again.
        let mut kept = self.kept.lock().unwrap_or_else(|poisoned| {
            let mut guard = poisoned.into_inner();
            self.release(guard.take());
            guard
        });
        let shape = (width, height, albedo.is_some(), normal.is_some());
        // SAFETY: the kept filter's buffers are `width * height` FLOAT3 pixels,
        // tightly packed, owned by it and alive until it is released; the
        // library reads the inputs and writes the output during the execution,
        // which returns before they are read here.
        let result = unsafe {
            self.prepare(&mut kept, threads, shape).map(|f| {
                f.color.copy_from_slice(color);
                if let Some(albedo) = albedo {
                    f.albedo.copy_from_slice(albedo);
                }
                if let Some(normal) = normal {
                    f.normal.copy_from_slice(normal);
                }
                (self.api.execute_filter)(f.filter);
            })
        };
        let checked = result.and_then(|()| {
            let device = kept.as_ref().expect("prepared").device;
            // SAFETY: a live device.
            unsafe { self.check(device) }
        });
        match checked {
            Ok(()) => Ok(kept.as_ref().and_then(|k| k.filters.first()).expect("prepared").output.clone()),
            Err(e) => {
                self.release(kept.take());
                Err(e)
            }
        }
    }

    /// The kept filter for `shape` on a device of `threads` threads, made (and
    /// committed) when none fits, moved to the front of the kept ones.
    unsafe fn prepare<'k>(
        &self,
        kept: &'k mut Option<Kept>,
        threads: usize,
        shape: (usize, usize, bool, bool),
    ) -> Result<&'k mut KeptFilter, String> {
        if kept.as_ref().is_some_and(|k| k.threads != threads) {
            self.release(kept.take());
        }
        if kept.is_none() {
            let device = (self.api.new_device)(DEVICE_TYPE_CPU);
            if device.is_null() {
                return Err(self.error(std::ptr::null_mut()).unwrap_or_else(|| "cannot create a CPU device".into()));
            }
            let made = kept.insert(Kept { device, threads, filters: Vec::new() });
            if threads > 0 {
                (self.api.set_device_int)(device, c"numThreads".as_ptr(), threads.min(c_int::MAX as usize) as c_int);
            }
            (self.api.commit_device)(device);
            self.check(made.device)?;
        }
        let k = kept.as_mut().expect("made above");
        if let Some(i) = k.filters.iter().position(|f| f.shape == shape) {
            // Moving the entry moves its `Vec`s' handles, not their heap buffers.
            let found = k.filters.remove(i);
            k.filters.insert(0, found);
        } else {
            if k.filters.len() == KEPT_FILTERS {
                let oldest = k.filters.pop().expect("full");
                (self.api.release_filter)(oldest.filter);
            }
            let filter = (self.api.new_filter)(k.device, c"RT".as_ptr());
            if filter.is_null() {
                return Err(self.error(k.device).unwrap_or_else(|| "cannot create the RT filter".into()));
            }
            let (width, height, with_albedo, with_normal) = shape;
            let floats = width * height * 3;
            let buffer = |given: bool| if given { vec![0.0f32; floats] } else { Vec::new() };
            k.filters.insert(
                0,
                KeptFilter {
                    filter,
                    shape,
                    color: buffer(true),
                    albedo: buffer(with_albedo),
                    normal: buffer(with_normal),
                    output: buffer(true),
                },
            );
            let f = &mut k.filters[0];
            let image = |name: &CStr, data: *mut f32| {
                (self.api.set_shared_filter_image)(filter, name.as_ptr(), data.cast(), FORMAT_FLOAT3, width, height, 0, 0, 0)
            };
            image(c"color", f.color.as_mut_ptr());
            if with_albedo {
                image(c"albedo", f.albedo.as_mut_ptr());
            }
            if with_normal {
                image(c"normal", f.normal.as_mut_ptr());
            }
            image(c"output", f.output.as_mut_ptr());
            (self.api.set_filter_bool)(filter, c"hdr".as_ptr(), true);
            (self.api.commit_filter)(filter);
            self.check(k.device)?;
        }
        Ok(&mut k.filters[0])
    }

    /// Releases a kept device and its filters, if any (the filters first: they hold their device).
    fn release(&self, kept: Option<Kept>) {
        let Some(k) = kept else { return };
        // SAFETY: both were made by this library and are released once, here.
        unsafe {
            for f in k.filters {
                (self.api.release_filter)(f.filter);
            }
            (self.api.release_device)(k.device);
        }
    }

    /// The device's first error since the last check, if any.
    unsafe fn error(&self, device: Device) -> Option<String> {
        let mut message: *const c_char = std::ptr::null();
        let code = (self.api.get_device_error)(device, &mut message);
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

impl Drop for Oidn {
    fn drop(&mut self) {
        // Before `_lib` unmaps the functions that release them.
        let kept = self.kept.get_mut().unwrap_or_else(PoisonError::into_inner).take();
        self.release(kept);
    }
}
