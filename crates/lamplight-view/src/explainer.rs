//! One explanation at a time per page, the newest winning, as renders are
//! ([`crate::renderer`]): a click replaces the click still waiting and cancels
//! the explanation in flight (it stops within
//! [`lamplight_core::explain::CANCEL_CHECK`] samples and answers nothing)
//! before the newest starts on the page's one worker, so sixty clicks cost one
//! explanation's time and memory, not sixty. Each explanation records at most
//! [`lamplight_core::explain::MAX_RECORDED_SAMPLES`] samples in full
//! (issue 30).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

/// An explanation to compute: it gets the cancel flag and returns the
/// answer to send, or `None` once cancelled.
pub type Work = Box<dyn FnOnce(Arc<AtomicBool>) -> Option<String> + Send>;

/// Sends an answer to the page.
type Answer = Box<dyn Fn(String) + Send>;

#[derive(Default)]
struct Slot {
    next: Option<(Work, Answer)>,
    running: bool,
    cancel: Arc<AtomicBool>,
    closed: bool,
}

/// A page's explainer: one worker, woken on demand.
#[derive(Clone, Default)]
pub struct Explainer {
    slot: Arc<Mutex<Slot>>,
}

impl Explainer {
    fn lock(&self) -> MutexGuard<'_, Slot> {
        self.slot.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Explains next with `work`, dropping the one waiting and cancelling
    /// the one in flight; `answer` sends what it returns unless a newer one
    /// came first.
    pub fn submit(&self, work: Work, answer: impl Fn(String) + Send + 'static) {
        let mut slot = self.lock();
        if slot.closed {
            return;
        }
        slot.next = Some((work, Box::new(answer)));
        slot.cancel.store(true, Ordering::Relaxed);
        if slot.running {
            return;
        }
        slot.running = true;
        drop(slot);
        let this = self.clone();
        tokio::task::spawn_blocking(move || loop {
            let (work, answer, cancel) = {
                let mut slot = this.lock();
                match slot.next.take() {
                    Some((work, answer)) if !slot.closed => {
                        slot.cancel = Arc::new(AtomicBool::new(false));
                        (work, answer, slot.cancel.clone())
                    }
                    _ => {
                        slot.running = false;
                        return;
                    }
                }
            };
            if let Some(reply) = work(cancel.clone()) {
                if !cancel.load(Ordering::Relaxed) {
                    answer(reply);
                }
            }
        });
    }

    /// Whether an explanation is running or waiting.
    pub fn busy(&self) -> bool {
        self.lock().running
    }

    /// The page went away: cancels the one in flight, drops the one waiting.
    pub fn close(&self) {
        let mut slot = self.lock();
        slot.closed = true;
        slot.next = None;
        slot.cancel.store(true, Ordering::Relaxed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;
    use std::time::{Duration, Instant};

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn sixty_clicks_run_one_at_a_time_and_the_newest_answers() {
        let explainer = Explainer::default();
        let (running, most, ran) = (Arc::new(AtomicUsize::new(0)), Arc::new(AtomicUsize::new(0)), Arc::new(AtomicUsize::new(0)));
        let answers = Arc::new(Mutex::new(Vec::new()));
        for click in 0..60 {
            let (running, most, ran) = (running.clone(), most.clone(), ran.clone());
            let work: Work = Box::new(move |cancel| {
                let now = running.fetch_add(1, Ordering::SeqCst) + 1;
                most.fetch_max(now, Ordering::SeqCst);
                ran.fetch_add(1, Ordering::SeqCst);
                // A long explanation that stops when cancelled.
                let start = Instant::now();
                while !cancel.load(Ordering::Relaxed) && start.elapsed() < Duration::from_millis(50) {
                    std::thread::sleep(Duration::from_millis(1));
                }
                running.fetch_sub(1, Ordering::SeqCst);
                (!cancel.load(Ordering::Relaxed)).then(|| format!("click {click}"))
            });
            let answers = answers.clone();
            // Sixty clicks in a burst.
            explainer.submit(work, move |a| answers.lock().unwrap().push(a));
        }
        let start = Instant::now();
        while explainer.busy() {
            assert!(start.elapsed() < Duration::from_secs(10));
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
        assert_eq!(most.load(Ordering::SeqCst), 1, "one worker: never two explanations at once");
        assert!(ran.load(Ordering::SeqCst) < 60, "waiting clicks were replaced: {} ran", ran.load(Ordering::SeqCst));
        // Only the newest answers, but for one that finished before the next click came.
        let answers = answers.lock().unwrap();
        assert_eq!(answers.last().map(String::as_str), Some("click 59"), "{answers:?}");
        assert!(answers.len() <= 3, "stale clicks answered: {answers:?}");
    }
}
