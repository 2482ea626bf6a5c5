//! Fair turns at the lab's workers: one queue per client, served in turn, so that one
//! client's maps cannot keep the others waiting.
//!
//! A computation needs a [`Turn`] to run (there are `--jobs` of them). Waiting requests are
//! queued per client, and a freed turn goes to the next client in round-robin order, not to
//! the oldest request: a client with six maps queued waits behind every other client's single
//! request. A long computation gives its turn back every [`SLICE`] while others wait (the
//! [`Budget`](super::limit::Budget) does so from inside the solvers, through the hook of its
//! cancellation token, and between the blocks of a map) and queues again behind them. Each
//! client may hold at most [`PER_CLIENT`] computations, waiting or running.

use std::collections::{HashMap, VecDeque};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;
use tokio::sync::oneshot;

/// Computations one client may hold at once, waiting or running; more are refused (429).
/// The page keeps at most one request of each kind in flight (it drops the stale one), so
/// four leaves room for a steady state, a simulation, a sweep and a map.
pub const PER_CLIENT: usize = 4;

/// How long a computation runs before it gives its turn to a waiting client.
pub const SLICE: Duration = Duration::from_millis(40);

/// The turns and their queues.
pub struct Fair {
    state: Mutex<State>,
}

struct State {
    /// Turns nobody holds.
    free: usize,
    /// Clients with waiting requests, in the order they are served; each with its own queue.
    queue: VecDeque<(String, VecDeque<oneshot::Sender<Turn>>)>,
    /// Computations held by each client, waiting or running.
    held: HashMap<String, usize>,
}

impl Fair {
    /// `jobs` turns (computations at once).
    pub fn new(jobs: usize) -> Arc<Self> {
        Arc::new(Self {
            state: Mutex::new(State {
                free: jobs.max(1),
                queue: VecDeque::new(),
                held: HashMap::new(),
            }),
        })
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        // The state stays consistent even if a holder panicked: every update is one step.
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A place for one more computation of `client`, or `None` when it holds
    /// [`PER_CLIENT`] already.
    pub fn slot(self: &Arc<Self>, client: &str) -> Option<Slot> {
        let mut state = self.lock();
        let held = state.held.entry(client.to_string()).or_insert(0);
        if *held >= PER_CLIENT {
            return None;
        }
        *held += 1;
        Some(Slot {
            fair: self.clone(),
            client: client.to_string(),
        })
    }

    /// Wait for a turn of `client`: at once when one is free and nobody waits, else when
    /// every client queued before it has had a turn.
    pub async fn turn(self: &Arc<Self>, client: &str) -> Turn {
        loop {
            let receiver = {
                let mut state = self.lock();
                if state.free > 0 && state.queue.is_empty() {
                    state.free -= 1;
                    return Turn {
                        fair: Some(self.clone()),
                    };
                }
                let (sender, receiver) = oneshot::channel();
                match state.queue.iter_mut().find(|(c, _)| c == client) {
                    Some((_, waiting)) => waiting.push_back(sender),
                    None => state
                        .queue
                        .push_back((client.to_string(), VecDeque::from([sender]))),
                }
                receiver
            };
            // A sender is only dropped unsent when its receiver is gone, so this holds a turn.
            if let Ok(turn) = receiver.await {
                return turn;
            }
        }
    }

    /// Whether any request waits for a turn.
    pub fn others_wait(&self) -> bool {
        !self.lock().queue.is_empty()
    }

    /// Hand a freed turn to the next waiting client (round robin), or keep it free.
    fn release(self: &Arc<Self>) {
        let mut state = self.lock();
        while let Some((client, mut waiting)) = state.queue.pop_front() {
            let Some(sender) = waiting.pop_front() else {
                continue;
            };
            if !waiting.is_empty() {
                state.queue.push_back((client, waiting));
            }
            match sender.send(Turn {
                fair: Some(self.clone()),
            }) {
                Ok(()) => return,
                // The request went away while it waited: disarm the turn, try the next one.
                Err(mut turn) => turn.fair = None,
            }
        }
        state.free += 1;
    }
}

/// The right to compute now; given back (to the next client in turn) when dropped.
pub struct Turn {
    fair: Option<Arc<Fair>>,
}

impl Drop for Turn {
    fn drop(&mut self) {
        if let Some(fair) = self.fair.take() {
            fair.release();
        }
    }
}

/// One of a client's [`PER_CLIENT`] places, freed when dropped.
pub struct Slot {
    fair: Arc<Fair>,
    client: String,
}

impl Drop for Slot {
    fn drop(&mut self) {
        let mut state = self.fair.lock();
        if let Some(held) = state.held.get_mut(&self.client) {
            *held -= 1;
            if *held == 0 {
                state.held.remove(&self.client);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test]
    async fn a_freed_turn_goes_to_the_next_client_not_the_oldest_request() {
        let fair = Fair::new(1);
        let first = fair.turn("a").await;
        // Client a queues three requests, then client b one.
        let mut waiting = Vec::new();
        for (i, client) in ["a", "a", "a", "b"].into_iter().enumerate() {
            let fair2 = fair.clone();
            waiting.push(tokio::spawn(async move {
                let turn = fair2.turn(client).await;
                (client, turn)
            }));
            // Queued in this order.
            while queued(&fair) < i + 1 {
                tokio::time::sleep(Duration::from_millis(1)).await;
            }
        }
        drop(first);
        let mut order = Vec::new();
        let mut handles = waiting;
        while !handles.is_empty() {
            let (done, _, rest) = futures_select(handles).await;
            let (client, turn) = done;
            order.push(client);
            drop(turn);
            handles = rest;
        }
        // a's first request, then b (the next client), then a's other two.
        assert_eq!(order, ["a", "b", "a", "a"]);
        assert_eq!(fair.lock().free, 1);
    }

    fn queued(fair: &Fair) -> usize {
        fair.lock().queue.iter().map(|(_, w)| w.len()).sum()
    }

    /// The first of `handles` to finish, its index, and the others.
    async fn futures_select<T: Send + 'static>(
        handles: Vec<tokio::task::JoinHandle<T>>,
    ) -> (T, usize, Vec<tokio::task::JoinHandle<T>>) {
        loop {
            if let Some(i) = handles.iter().position(|h| h.is_finished()) {
                let mut handles = handles;
                let done = handles.remove(i).await.unwrap();
                return (done, i, handles);
            }
            tokio::time::sleep(Duration::from_millis(1)).await;
        }
    }

    #[tokio::test]
    async fn a_request_that_went_away_passes_its_turn_on() {
        let fair = Fair::new(1);
        let first = fair.turn("a").await;
        let gone = {
            let fair = fair.clone();
            tokio::spawn(async move { fair.turn("b").await })
        };
        while !fair.others_wait() {
            tokio::task::yield_now().await;
        }
        gone.abort();
        let _ = gone.await;
        let waiting = {
            let fair = fair.clone();
            tokio::spawn(async move { fair.turn("c").await })
        };
        while fair.lock().queue.len() < 2 {
            tokio::task::yield_now().await;
        }
        drop(first);
        let turn = tokio::time::timeout(Duration::from_secs(10), waiting)
            .await
            .expect("c gets the turn b left")
            .unwrap();
        drop(turn);
        assert_eq!(fair.lock().free, 1);
        assert!(fair.lock().queue.is_empty());
    }

    #[test]
    fn a_client_holds_at_most_its_share() {
        let fair = Fair::new(2);
        let slots: Vec<_> = (0..PER_CLIENT).map(|_| fair.slot("a").unwrap()).collect();
        assert!(fair.slot("a").is_none());
        assert!(fair.slot("b").is_some());
        drop(slots);
        assert!(fair.slot("a").is_some());
    }
}
