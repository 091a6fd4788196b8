//! Typed errors: a capture that cannot be read at all, and why a packet inside one was
//! skipped.

/// A capture that cannot be read (nothing in it is usable).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum CaptureError {
    /// The bytes start with neither the pcap nor the pcapng magic.
    #[error("not a pcap or pcapng capture (first bytes {first:02x?})")]
    NotACapture {
        /// Up to the first four bytes.
        first: Vec<u8>,
    },
    /// The pcap global header or the first pcapng section header cannot be parsed.
    #[error("{format} header unreadable: {what}")]
    BadHeader {
        /// `pcap` or `pcapng`.
        format: &'static str,
        /// What is wrong.
        what: String,
    },
    /// A pcap file whose link type carries no IP this reader knows (Ethernet 1, raw IP
    /// 101, IPv4 228, IPv6 229, Linux cooked capture 113).
    #[error(
        "pcap link type {linktype} is not supported (Ethernet 1, raw IP 101/228/229, Linux SLL 113)"
    )]
    UnsupportedLinkType {
        /// The header's link type.
        linktype: i32,
    },
    /// A datagram too long for one IPv4/UDP packet, or a time that pcap cannot hold.
    #[error("packet {packet} cannot be written: {what}")]
    Write {
        /// Index of the datagram.
        packet: usize,
        /// What is wrong.
        what: String,
    },
}

/// Why one packet gave no UDP payload.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SkipReason {
    /// The link, IP or UDP headers are malformed or cut short (etherparse's message).
    #[error("malformed headers: {what}")]
    Malformed {
        /// What etherparse found.
        what: String,
    },
    /// Not an IP packet (e.g. ARP) or IP without a transport slice.
    #[error("not an IP packet")]
    NotIp,
    /// An IP packet that does not carry UDP.
    #[error("not UDP (IP protocol {protocol})")]
    NotUdp {
        /// The IP protocol number (6 TCP, 1 ICMP, …).
        protocol: u8,
    },
    /// A fragment of a fragmented IP datagram (not reassembled).
    #[error("IP fragment (not reassembled)")]
    Fragment,
    /// A pcapng packet on an interface of an unsupported link type.
    #[error("interface {interface}: link type {linktype} is not supported")]
    LinkType {
        /// Interface id.
        interface: u32,
        /// Its link type.
        linktype: i32,
    },
    /// A pcapng packet naming an interface not described before it.
    #[error("interface {interface} is not described in its section")]
    UnknownInterface {
        /// Interface id.
        interface: u32,
    },
    /// The last record or block is cut short: the rest of the file is lost.
    #[error("truncated {what}: {have} bytes left")]
    Truncated {
        /// `pcap record` or `pcapng block`.
        what: &'static str,
        /// Bytes left in the file from its start.
        have: usize,
    },
    /// A pcapng block that cannot be parsed: its length is unusable, so the rest of
    /// the file is lost.
    #[error("unparsable pcapng block")]
    BadBlock,
    /// A timestamp that does not fit (pcapng resolution or offset out of range).
    #[error("timestamp out of range")]
    Timestamp,
}

/// A packet (or the tail of the file) skipped, with its reason.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Skipped {
    /// Index of the packet among the file's packet records (0-based).
    pub packet: usize,
    /// Byte offset of its record in the file.
    pub offset: usize,
    /// Why.
    pub reason: SkipReason,
}
