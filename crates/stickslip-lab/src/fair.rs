//! Fair turns at the lab's workers: one queue per client, and the clients of one address
//! served as one, so that neither one client's maps nor one computer's many connections can
//! keep the others waiting.
//!
//! A computation needs a [`Turn`] to run (there are `--jobs` of them). Waiting requests are
//! queued per [`Client`], the clients grouped by their address, and a freed turn goes to the
//! next *address* in round-robin order, and there to its next client in round-robin order,
//! not to the oldest request: a client with six maps queued waits behind every other client's
//! single request, and a script that opens a hundred connections from one computer (each a
//! client of its own, without the page's id) gets the turns of one computer, as a student's
//! page does. A long computation gives its turn back every [`SLICE`] while others wait (the
//! [`Budget`](super::limit::Budget) does so from inside the solvers, through the hook of its
//! cancellation token, and between the blocks of a map) and queues again behind them. Each
//! client may hold at most [`PER_CLIENT`] computations, waiting or running (and each address
//! at most [`MAX_PER_ADDRESS`](super::serve::MAX_PER_ADDRESS) connections: see
//! [`serve`](super::serve)).

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

/// Who asks for a computation: the address the request comes from, and the client there (the
/// page's own id, or else the connection).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Client {
    /// The peer's IP address (`local` for a request that came through no socket).
    pub address: String,
    /// The page's id (`X-Lab-Client`), or `:port` for a connection without one.
    pub id: String,
}

impl Client {
    /// The client `id` at `address`.
    pub fn new(address: impl Into<String>, id: impl Into<String>) -> Self {
        Self {
            address: address.into(),
            id: id.into(),
        }
    }
}

impl std::fmt::Display for Client {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {}", self.address, self.id)
    }
}

/// The turns and their queues.
pub struct Fair {
    state: Mutex<State>,
}

/// One address's waiting clients, in the order they are served, each with its own queue.
struct Waiting {
    address: String,
    clients: VecDeque<(String, VecDeque<oneshot::Sender<Turn>>)>,
}

struct State {
    /// Turns nobody holds.
    free: usize,
    /// Addresses with waiting requests, in the order they are served.
    queue: VecDeque<Waiting>,
    /// Computations held by each client, waiting or running.
    held: HashMap<Client, usize>,
    /// Turns given so far, and for each request that waited, its client and the turns given
    /// to others while it waited (what the tests compare).
    #[cfg(test)]
    given: u64,
    #[cfg(test)]
    waits: Vec<(Client, u64)>,
}

impl State {
    /// The next request to serve: the next address's next client's oldest request that is
    /// still waiting (requests that went away are dropped).
    fn next_waiting(&mut self) -> Option<oneshot::Sender<Turn>> {
        while let Some(mut at) = self.queue.pop_front() {
            for (_, waiting) in &mut at.clients {
                waiting.retain(|s| !s.is_closed());
            }
            at.clients.retain(|(_, waiting)| !waiting.is_empty());
            let Some((client, mut waiting)) = at.clients.pop_front() else {
                continue;
            };
            let sender = waiting.pop_front();
            if !waiting.is_empty() {
                at.clients.push_back((client, waiting));
            }
            if !at.clients.is_empty() {
                self.queue.push_back(at);
            }
            if sender.is_some() {
                return sender;
            }
        }
        None
    }
}

impl Fair {
    /// `jobs` turns (computations at once).
    pub fn new(jobs: usize) -> Arc<Self> {
        Arc::new(Self {
            state: Mutex::new(State {
                free: jobs.max(1),
                queue: VecDeque::new(),
                held: HashMap::new(),
                #[cfg(test)]
                given: 0,
                #[cfg(test)]
                waits: Vec::new(),
            }),
        })
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        // The state stays consistent even if a holder panicked: every update is one step.
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A place for one more computation of `client`, or `None` when it holds
    /// [`PER_CLIENT`] already.
    pub fn slot(self: &Arc<Self>, client: &Client) -> Option<Slot> {
        let mut state = self.lock();
        let held = state.held.entry(client.clone()).or_insert(0);
        if *held >= PER_CLIENT {
            return None;
        }
        *held += 1;
        Some(Slot {
            fair: self.clone(),
            client: client.clone(),
        })
    }

    /// Wait for a turn of `client`: at once when one is free and nobody waits, else when
    /// every address queued before its address has had a turn (and, at its address, every
    /// client queued before it).
    pub async fn turn(self: &Arc<Self>, client: &Client) -> Turn {
        loop {
            #[cfg(test)]
            let queued_at;
            let receiver = {
                let mut state = self.lock();
                if state.free > 0 && !state.others_wait() {
                    state.free -= 1;
                    #[cfg(test)]
                    {
                        state.given += 1;
                    }
                    return Turn {
                        fair: Some(self.clone()),
                    };
                }
                #[cfg(test)]
                {
                    queued_at = state.given;
                }
                let (sender, receiver) = oneshot::channel();
                let at = match state.queue.iter().position(|a| a.address == client.address) {
                    Some(i) => &mut state.queue[i],
                    None => {
                        state.queue.push_back(Waiting {
                            address: client.address.clone(),
                            clients: VecDeque::new(),
                        });
                        state.queue.back_mut().expect("just pushed")
                    }
                };
                match at.clients.iter_mut().find(|(c, _)| *c == client.id) {
                    Some((_, waiting)) => waiting.push_back(sender),
                    None => at
                        .clients
                        .push_back((client.id.clone(), VecDeque::from([sender]))),
                }
                receiver
            };
            // A sender is only dropped unsent when its receiver is gone, so this holds a turn.
            if let Ok(turn) = receiver.await {
                #[cfg(test)]
                {
                    let mut state = self.lock();
                    let others = state.given - queued_at - 1;
                    state.waits.push((client.clone(), others));
                }
                return turn;
            }
        }
    }

    /// Whether any request waits for a turn.
    pub fn others_wait(&self) -> bool {
        self.lock().others_wait()
    }

    /// Hand a freed turn to the next waiting request (round robin over the addresses, then
    /// over each address's clients), or keep it free.
    fn release(self: &Arc<Self>) {
        let mut state = self.lock();
        while let Some(sender) = state.next_waiting() {
            #[cfg(test)]
            {
                state.given += 1;
            }
            match sender.send(Turn {
                fair: Some(self.clone()),
            }) {
                Ok(()) => return,
                // The request went away while it waited: disarm the turn, try the next one.
                Err(mut turn) => {
                    turn.fair = None;
                    #[cfg(test)]
                    {
                        state.given -= 1;
                    }
                }
            }
        }
        state.free += 1;
    }

    /// For each request that waited for its turn so far: its client and how many turns were
    /// given to other requests meanwhile.
    #[cfg(test)]
    pub fn waits(&self) -> Vec<(Client, u64)> {
        self.lock().waits.clone()
    }

    /// Computations held now (waiting or running) by the clients at `address`.
    #[cfg(test)]
    pub fn held_at(&self, address: &str) -> usize {
        let state = self.lock();
        state
            .held
            .iter()
            .filter(|(c, _)| c.address == address)
            .map(|(_, n)| n)
            .sum()
    }
}

impl State {
    /// Whether a request that has not gone away waits for a turn.
    fn others_wait(&self) -> bool {
        self.queue
            .iter()
            .flat_map(|a| &a.clients)
            .flat_map(|(_, waiting)| waiting)
            .any(|s| !s.is_closed())
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
    client: Client,
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

    /// Client `id` at `address`.
    fn at(address: &str, id: &str) -> Client {
        Client::new(address, id)
    }

    /// Requests `order` queued in this order while the only turn is held, then served one
    /// after the other: the order they got their turns in.
    async fn served(order: &[Client]) -> Vec<Client> {
        let fair = Fair::new(1);
        let first = fair.turn(&at("0.0.0.0", "first")).await;
        let mut waiting = Vec::new();
        for (i, client) in order.iter().cloned().enumerate() {
            let fair2 = fair.clone();
            waiting.push(tokio::spawn(async move {
                let turn = fair2.turn(&client).await;
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
        assert_eq!(fair.lock().free, 1);
        order
    }

    #[tokio::test]
    async fn a_freed_turn_goes_to_the_next_client_not_the_oldest_request() {
        // Client a queues three requests, then client b one (the same address).
        let (a, b) = (at("10.0.0.1", "a"), at("10.0.0.1", "b"));
        let order = served(&[a.clone(), a.clone(), a.clone(), b.clone()]).await;
        // a's first request, then b (the next client), then a's other two.
        assert_eq!(order, [a.clone(), b, a.clone(), a]);
    }

    #[tokio::test]
    async fn a_freed_turn_goes_to_the_next_address_then_to_its_next_client() {
        // A script at one address queues a request on each of four connections (four
        // clients, none with the page's id); then two students at addresses of their own.
        let script: Vec<Client> = (0..4).map(|k| at("10.0.0.66", &format!(":{k}"))).collect();
        let (s1, s2) = (at("10.0.0.1", "page-1"), at("10.0.0.2", "page-2"));
        let mut order = script.clone();
        order.extend([s1.clone(), s2.clone()]);
        let got = served(&order).await;
        // The script's address has one turn in each round, its connections in turn.
        assert_eq!(
            got,
            [
                script[0].clone(),
                s1,
                s2,
                script[1].clone(),
                script[2].clone(),
                script[3].clone()
            ]
        );
    }

    fn queued(fair: &Fair) -> usize {
        fair.lock()
            .queue
            .iter()
            .flat_map(|a| &a.clients)
            .map(|(_, w)| w.len())
            .sum()
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
        let first = fair.turn(&at("10.0.0.1", "a")).await;
        let gone = {
            let fair = fair.clone();
            tokio::spawn(async move { fair.turn(&at("10.0.0.2", "b")).await })
        };
        while !fair.others_wait() {
            tokio::task::yield_now().await;
        }
        gone.abort();
        let _ = gone.await;
        // Nobody waits now: b's place is not a waiting request.
        assert!(!fair.others_wait());
        let waiting = {
            let fair = fair.clone();
            tokio::spawn(async move { fair.turn(&at("10.0.0.3", "c")).await })
        };
        while !fair.others_wait() {
            tokio::task::yield_now().await;
        }
        drop(first);
        let turn = waiting.await.expect("c gets the turn b left");
        drop(turn);
        assert_eq!(fair.lock().free, 1);
        assert!(!fair.others_wait());
    }

    #[test]
    fn a_client_holds_at_most_its_share() {
        let fair = Fair::new(2);
        let a = at("10.0.0.1", "a");
        let slots: Vec<_> = (0..PER_CLIENT).map(|_| fair.slot(&a).unwrap()).collect();
        assert!(fair.slot(&a).is_none());
        assert!(fair.slot(&at("10.0.0.1", "b")).is_some());
        // The same id at another address is another client.
        assert!(fair.slot(&at("10.0.0.2", "a")).is_some());
        drop(slots);
        assert!(fair.slot(&a).is_some());
    }
}
