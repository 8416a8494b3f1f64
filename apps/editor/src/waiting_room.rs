//! [`WaitingRoom`]: the connections that have not sent their request head yet. Such a
//! connection cannot be told apart from the page's own requests until its head arrives (the
//! token is in it), so idle connections must never keep the page out: the room has a fixed
//! capacity, and a connection that arrives when it is full closes the one that has waited
//! longest. The page sends its head at once and gets through; a client that opens connections
//! and sends nothing only closes its own earlier ones.

use std::collections::VecDeque;
use std::net::{Shutdown, TcpStream};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// Connections waiting for their request head; see the [module](self).
#[derive(Debug)]
pub struct WaitingRoom {
    capacity: usize,
    /// The waiting connections (a handle to each, to close it), oldest first.
    waiting: Mutex<VecDeque<(u64, TcpStream)>>,
    next_ticket: AtomicU64,
}

/// A connection's place in the [`WaitingRoom`]; leaves it when dropped.
#[derive(Debug)]
pub struct Ticket<'r> {
    room: &'r WaitingRoom,
    number: u64,
}

impl WaitingRoom {
    /// A room for `capacity` connections (at least one).
    pub fn new(capacity: usize) -> Self {
        Self {
            capacity: capacity.max(1),
            waiting: Mutex::new(VecDeque::new()),
            next_ticket: AtomicU64::new(0),
        }
    }

    /// Lets `stream` wait for its head; when the room is full, the connection that has waited
    /// longest is closed (its reads end at once) to make room. Without a handle to the stream
    /// (the system refused to duplicate it) it waits unregistered, bounded by its deadline.
    pub fn enter(&self, stream: &TcpStream) -> Ticket<'_> {
        let number = self.next_ticket.fetch_add(1, Ordering::Relaxed);
        let mut waiting = self.waiting.lock().unwrap_or_else(|e| e.into_inner());
        while waiting.len() >= self.capacity {
            if let Some((_, oldest)) = waiting.pop_front() {
                let _ = oldest.shutdown(Shutdown::Both);
            }
        }
        if let Ok(handle) = stream.try_clone() {
            waiting.push_back((number, handle));
        }
        Ticket { room: self, number }
    }
}

impl Drop for Ticket<'_> {
    fn drop(&mut self) {
        let mut waiting = self.room.waiting.lock().unwrap_or_else(|e| e.into_inner());
        waiting.retain(|(number, _)| *number != self.number);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;
    use std::net::TcpListener;

    fn waiting(room: &WaitingRoom) -> usize {
        room.waiting.lock().unwrap().len()
    }

    #[test]
    fn a_full_room_closes_the_connection_waiting_longest() {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let address = listener.local_addr().unwrap();
        let room = WaitingRoom::new(2);
        let mut accepted = Vec::new();
        let mut clients = Vec::new();
        for _ in 0..3 {
            clients.push(TcpStream::connect(address).unwrap());
            accepted.push(listener.accept().unwrap().0);
        }
        let first = room.enter(&accepted[0]);
        let second = room.enter(&accepted[1]);
        assert_eq!(waiting(&room), 2);
        let third = room.enter(&accepted[2]);
        assert_eq!(waiting(&room), 2);
        // The first connection was closed: its reads end, the others' do not.
        let mut byte = [0u8; 1];
        assert_eq!(accepted[0].read(&mut byte).unwrap(), 0);
        accepted[1]
            .set_read_timeout(Some(std::time::Duration::from_millis(50)))
            .unwrap();
        assert!(
            accepted[1].read(&mut byte).is_err(),
            "still open, nothing sent"
        );
        drop((first, second, third));
        assert_eq!(waiting(&room), 0);
    }
}
