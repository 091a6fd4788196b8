//! Packet captures of UDP datagrams for Argus: pcap and pcapng files read into the UDP
//! payloads they carry, each with its capture time, and pcap files written from
//! payloads (so Argus can produce a capture a recorder or a decoder reads).
//!
//! The format is known by content ([`Format::sniff`]): the pcap magic (either byte
//! order, micro- or nanosecond timestamps), the pcapng section-header magic, or else
//! not a capture at all (a raw file, e.g. concatenated ASTERIX blocks, which the
//! caller decodes itself).
//!
//! # Robustness
//! [`read`] never panics and always terminates. A file whose header cannot be read,
//! or a pcap file of a link type without IP, is an error ([`CaptureError`]); inside a
//! readable file every packet that gives no UDP payload is skipped and reported as a
//! [`Skipped`] packet with a typed [`SkipReason`] (not UDP, malformed headers, an IP
//! fragment, an interface of an unsupported link type, a truncated last record), and
//! the rest of the file is kept.
//!
//! # Crates
//! Compared December 2026: `pcap-parser` 0.17 (rusticata; pcap and pcapng, both byte
//! orders, pcapng timestamp resolution and offset per interface, zero-copy slices,
//! fuzzed; writing through its `serialize` feature) and `pcap-file` 2.0 (pcap and
//! pcapng reader and writer; its last release is from 2022, 3.0 still a release
//! candidate). `pcap-parser` is used for the file framing. The link, IP and UDP
//! headers are `etherparse` 0.21's (Ethernet II with VLAN tags, Linux cooked capture,
//! raw IPv4 / IPv6 with extension headers; it also builds the frames written).
//!
//! # Example
//! ```
//! use argus_capture::{Datagram, Endpoints, Format, read, write_pcap};
//! use std::time::Duration;
//!
//! let payload = [48u8, 0, 3];
//! let d = Datagram { time: Some(Duration::from_millis(1500)), payload: &payload, packet: 0 };
//! let bytes = write_pcap(&[d], &Endpoints::default())?;
//! assert_eq!(Format::sniff(&bytes), Format::Pcap);
//! let back = read(&bytes)?;
//! assert!(back.skipped.is_empty());
//! assert_eq!(back.datagrams[0].payload, &payload);
//! assert_eq!(back.datagrams[0].time, Some(Duration::from_millis(1500)));
//! # Ok::<(), argus_capture::CaptureError>(())
//! ```

mod error;
mod link;
mod read;
mod write;

pub use error::{CaptureError, SkipReason, Skipped};
pub use read::{Capture, Datagram, read};
pub use write::{Endpoints, MAX_PAYLOAD, write_pcap};

/// What a file holds, known by its first bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// A pcap file (magic `a1b2c3d4` or `a1b23c4d`, either byte order).
    Pcap,
    /// A pcapng file (section header block type `0a0d0d0a`).
    PcapNg,
    /// Not a packet capture.
    Other,
}

impl Format {
    /// The format of `bytes` by its magic number.
    #[must_use]
    pub fn sniff(bytes: &[u8]) -> Self {
        match bytes.get(..4) {
            Some([0xd4, 0xc3, 0xb2, 0xa1] | [0xa1, 0xb2, 0xc3, 0xd4])
            | Some([0x4d, 0x3c, 0xb2, 0xa1] | [0xa1, 0xb2, 0x3c, 0x4d]) => Self::Pcap,
            Some([0x0a, 0x0d, 0x0d, 0x0a]) => Self::PcapNg,
            _ => Self::Other,
        }
    }
}
