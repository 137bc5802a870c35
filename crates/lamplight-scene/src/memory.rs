//! The memory budget of a load and render: meshes, textures, environment maps,
//! acceleration structures and the film draw on one figure, so that a small
//! input that declares a huge size (a `.serialized` mesh of 2^24 vertices in
//! 600 KB, an 8192x8192 PNG of a few hundred KB) is refused with one line
//! instead of aborting the process when an allocation fails.
//!
//! Each reader asks for its share with [`reserve`] *before* it allocates, from
//! sizes it knows up front: an image's header dimensions, a mesh's declared
//! vertex and triangle counts, a film's pixel count. A request over what is
//! left is an [`Exceeded`] naming what needed it, how much, and the option that
//! raises the budget. The figures are estimates of the peak (decoding buffers
//! included), not a tally of every allocation: the point is that no input can
//! ask for more than the budget, not an exact account.
//!
//! The budget is process-wide: a front end sets it with [`begin`] before it
//! reads a scene (the command line once per process, Python once per call), and
//! [`set_limit`] applies a scene's own `[render] memory_budget` once its
//! settings are read. The default is [`DEFAULT_FRACTION`] of the memory the
//! machine has available (Linux `/proc/meminfo` `MemAvailable`), or
//! [`FALLBACK_BYTES`] where that cannot be read. Readers called without a front
//! end (the library's tests, fuzz targets) run under the default too.

use std::sync::atomic::{AtomicU64, AtomicU8, Ordering};

use crate::request::Naming;

/// The share of the machine's available memory a render may use by default.
pub const DEFAULT_FRACTION: f64 = 0.25;
/// The default budget where the machine's memory cannot be read: 4 GiB.
pub const FALLBACK_BYTES: u64 = 4 << 30;
/// The smallest budget one may set: 16 MiB (less could not hold a small film).
pub const MIN_BYTES: u64 = 16 << 20;

/// 0 until a front end or the first reader sets it.
static LIMIT: AtomicU64 = AtomicU64::new(0);
static USED: AtomicU64 = AtomicU64::new(0);
/// How the front end spells the option: 0 flags, 1 keywords.
static NAMING: AtomicU8 = AtomicU8::new(0);

/// A share that did not fit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Exceeded {
    /// What asked (`mesh.serialized: 16777216 vertices and 16777216 triangles`).
    pub what: String,
    /// The bytes it asked for.
    pub needed: u64,
    /// What others had taken already.
    pub used: u64,
    /// The budget.
    pub limit: u64,
    /// The front end's spelling of the option.
    pub naming: Naming,
}

impl std::fmt::Display for Exceeded {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let raise = match self.naming {
            Naming::Flags => "--memory-budget (or [render] memory_budget in a TOML scene)",
            Naming::Keywords => "memory_budget= (or [render] memory_budget in a TOML scene)",
        };
        write!(f, "{} needs {} of memory", self.what, bytes(self.needed))?;
        if self.used > 0 {
            write!(f, ", and {} of the memory budget of {} is in use", bytes(self.used), bytes(self.limit))?;
        } else {
            write!(f, ", more than the memory budget of {}", bytes(self.limit))?;
        }
        write!(f, "; raise it with {raise}")
    }
}

/// Starts a load and render under `limit` bytes (`None`: the default), with
/// nothing reserved yet; messages spell the option by `naming`.
pub fn begin(limit: Option<u64>, naming: Naming) {
    NAMING.store(matches!(naming, Naming::Keywords) as u8, Ordering::Relaxed);
    USED.store(0, Ordering::Relaxed);
    LIMIT.store(limit.unwrap_or_else(default_limit), Ordering::Relaxed);
}

/// Counts afresh under the same budget: a scene is being built again (a
/// viewer's reload, another Python `Scene`), and what the last build took is
/// its own.
pub fn restart() {
    USED.store(0, Ordering::Relaxed);
}

/// Changes the budget of the load under way (a scene's own setting), keeping
/// what is reserved.
pub fn set_limit(limit: u64) {
    LIMIT.store(limit, Ordering::Relaxed);
}

/// The budget in bytes.
pub fn limit() -> u64 {
    match LIMIT.load(Ordering::Relaxed) {
        0 => {
            let l = default_limit();
            // A racing `begin` wins: only an unset limit is replaced.
            let _ = LIMIT.compare_exchange(0, l, Ordering::Relaxed, Ordering::Relaxed);
            LIMIT.load(Ordering::Relaxed)
        }
        l => l,
    }
}

/// The bytes reserved so far.
pub fn used() -> u64 {
    USED.load(Ordering::Relaxed)
}

/// Takes `bytes` of the budget for `what` (called only on failure, for the
/// message), or says it does not fit; nothing is taken then.
pub fn reserve(bytes: u64, what: impl FnOnce() -> String) -> Result<(), Exceeded> {
    let limit = limit();
    let mut used = USED.load(Ordering::Relaxed);
    loop {
        let total = used.saturating_add(bytes);
        if total > limit {
            let naming = if NAMING.load(Ordering::Relaxed) == 1 { Naming::Keywords } else { Naming::Flags };
            return Err(Exceeded { what: what(), needed: bytes, used, limit, naming });
        }
        match USED.compare_exchange_weak(used, total, Ordering::Relaxed, Ordering::Relaxed) {
            Ok(_) => return Ok(()),
            Err(now) => used = now,
        }
    }
}

/// Gives back `bytes` a reader reserved for a buffer it has freed (a decoder's).
pub fn release(bytes: u64) {
    let _ = USED.fetch_update(Ordering::Relaxed, Ordering::Relaxed, |u| Some(u.saturating_sub(bytes)));
}

/// [`DEFAULT_FRACTION`] of `MemAvailable`, or [`FALLBACK_BYTES`].
pub fn default_limit() -> u64 {
    let available = std::fs::read_to_string("/proc/meminfo").ok().and_then(|text| mem_available(&text));
    match available {
        Some(b) => ((b as f64 * DEFAULT_FRACTION) as u64).max(MIN_BYTES),
        None => FALLBACK_BYTES,
    }
}

/// `MemAvailable` (else `MemTotal`) of `/proc/meminfo`'s text, in bytes.
fn mem_available(text: &str) -> Option<u64> {
    let field = |name: &str| {
        text.lines().find_map(|l| l.strip_prefix(name)?.trim().strip_suffix("kB")?.trim().parse::<u64>().ok()).map(|kb| kb * 1024)
    };
    field("MemAvailable:").or_else(|| field("MemTotal:"))
}

/// A size for messages: `512 MiB`, `3.2 GiB`, `800 bytes`.
pub fn bytes(n: u64) -> String {
    const KIB: u64 = 1 << 10;
    const MIB: u64 = 1 << 20;
    const GIB: u64 = 1 << 30;
    match n {
        n if n >= GIB => format!("{:.1} GiB", n as f64 / GIB as f64),
        n if n >= MIB => format!("{:.1} MiB", n as f64 / MIB as f64),
        n if n >= KIB => format!("{:.1} KiB", n as f64 / KIB as f64),
        n => format!("{n} bytes"),
    }
}

/// Parses a budget as written by a user: bytes with an optional binary unit,
/// `K`, `M`, `G`, `T` (also `KiB`, `MB`, ...: every unit is a power of 1024),
/// such as `4G`, `512M`, `1.5G`. At least [`MIN_BYTES`].
pub fn parse(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let split = t.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let scale: u64 = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1,
        "k" | "kb" | "kib" => 1 << 10,
        "m" | "mb" | "mib" => 1 << 20,
        "g" | "gb" | "gib" => 1 << 30,
        "t" | "tb" | "tib" => 1 << 40,
        _ => return Err(format!("expected a size such as 4G, 512M or 1.5G, got \"{text}\"")),
    };
    let value: f64 = number.parse().map_err(|_| format!("expected a size such as 4G, 512M or 1.5G, got \"{text}\""))?;
    let total = value * scale as f64;
    if !(total.is_finite() && total >= MIN_BYTES as f64 && total < u64::MAX as f64) {
        return Err(format!("must be at least {} (16M), got \"{text}\"", bytes(MIN_BYTES)));
    }
    Ok(total as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_in_binary_units() {
        assert_eq!(parse("4G"), Ok(4 << 30));
        assert_eq!(parse("512M"), Ok(512 << 20));
        assert_eq!(parse("1.5GiB"), Ok(3 << 29));
        assert_eq!(parse("17179869184"), Ok(16 << 30));
        assert_eq!(parse("1M"), Err("must be at least 16.0 MiB (16M), got \"1M\"".to_string()));
        assert_eq!(parse("lots"), Err("expected a size such as 4G, 512M or 1.5G, got \"lots\"".to_string()));
        assert_eq!(parse("4X"), Err("expected a size such as 4G, 512M or 1.5G, got \"4X\"".to_string()));
    }

    #[test]
    fn meminfo_gives_available_memory() {
        let text = "MemTotal:       24000000 kB\nMemFree:        1000 kB\nMemAvailable:   16000000 kB\n";
        assert_eq!(mem_available(text), Some(16_000_000 * 1024));
        assert_eq!(mem_available("MemTotal:  2048 kB\n"), Some(2048 * 1024));
        assert_eq!(mem_available("nothing"), None);
        assert_eq!(bytes(3 << 29), "1.5 GiB");
        assert_eq!(bytes(800), "800 bytes");
    }
}
