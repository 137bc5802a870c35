//! Large buffers backed by huge pages where Linux offers them: the film's and
//! the BVH build's.
//!
//! A 1280x720 render fills about 25 MB of fresh memory (the film, the image,
//! its 8-bit copy). In 4 KiB pages that is some 6,600 page faults, each a trip
//! into the kernel; in a 2-thread Whitted render of `luxo` they cost about 3 %
//! of the whole process (BENCHMARKS.md, session 25). Building the BVH of a
//! million triangles writes some 200 MB of fresh memory before its threads
//! start, about a tenth of loading the mesh (session 27). Transparent huge pages in
//! their `madvise` mode (the kernel's usual default) back a region the program
//! advises `MADV_HUGEPAGE` with 2 MiB pages instead: 512 times fewer faults,
//! the same bytes. The advice goes on the freshly allocated, not yet touched
//! buffer (a zeroed allocation this large comes straight from `mmap`), and
//! only on whole 2 MiB blocks inside it. It changes no contents and may be
//! ignored (THP `never`, other systems): the buffer is the same either way.
//!
//! The system call is the only way to ask for this; no allocator crate does it
//! for a single buffer, hence `libc` directly.

/// A vector of `n` copies of `zero`, which must be all zero bits (so that the
/// allocation is a fresh zeroed mapping), advised for huge pages when large.
pub(crate) fn zeroed<T: Clone>(zero: T, n: usize) -> Vec<T> {
    let v = vec![zero; n];
    advise_huge(&v);
    v
}

/// An empty vector with room for `n` values, the room advised for huge pages
/// when large (a fresh allocation this large comes untouched from `mmap`).
pub(crate) fn with_capacity<T>(n: usize) -> Vec<T> {
    let v: Vec<T> = Vec::with_capacity(n);
    advise_range(v.as_ptr() as usize, n * std::mem::size_of::<T>());
    v
}

/// Bytes in a huge page on x86-64 and most of aarch64's configurations.
const HUGE: usize = 2 << 20;

/// Asks the kernel to back the whole 2 MiB blocks of `buffer` with huge pages.
fn advise_huge<T>(buffer: &[T]) {
    advise_range(buffer.as_ptr() as usize, std::mem::size_of_val(buffer));
}

/// [`advise_huge`] for the `bytes` bytes of an allocation from address `start`.
#[cfg(target_os = "linux")]
fn advise_range(start: usize, bytes: usize) {
    if bytes < 2 * HUGE {
        return;
    }
    let first = start.next_multiple_of(HUGE);
    let end = (start + bytes) / HUGE * HUGE;
    if end > first {
        // SAFETY: the range lies inside the allocation, which this
        // process owns; the advice changes how pages are backed, never their
        // contents, and a refusal (EINVAL without THP) leaves the buffer as is.
        unsafe {
            libc::madvise(first as *mut libc::c_void, end - first, libc::MADV_HUGEPAGE);
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise_range(_start: usize, _bytes: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buffers_are_zero_and_writable_at_any_size() {
        for n in [0, 1, 1000, (5 * HUGE) / 12 + 7] {
            let mut v = zeroed([0.0f32; 3], n);
            assert_eq!(v.len(), n);
            assert!(v.iter().all(|p| *p == [0.0; 3]));
            if let Some(last) = v.last_mut() {
                *last = [1.0, 2.0, 3.0];
                v[0][0] += 0.5;
            }
            if n > 1 {
                assert_eq!((v[0][0], v[n - 1]), (0.5, [1.0, 2.0, 3.0]));
                assert!(v[1..n - 1].iter().all(|p| *p == [0.0; 3]), "the rest stays zero");
            }
        }
    }

    #[test]
    fn reserved_buffers_fill_at_any_size() {
        for n in [0, 1, 1000, (5 * HUGE) / 24 + 7] {
            let mut v = with_capacity::<[f64; 3]>(n);
            assert!(v.is_empty() && v.capacity() >= n);
            v.extend((0..n).map(|i| [i as f64; 3]));
            assert!(v.iter().enumerate().all(|(i, p)| *p == [i as f64; 3]));
        }
    }
}
