//! Reading a pcap or pcapng capture into its UDP payloads.

use std::time::Duration;

use pcap_parser::nom;
use pcap_parser::pcapng::Block;
use pcap_parser::{
    LegacyPcapBlock, PcapError, parse_block_be, parse_block_le, parse_pcap_frame,
    parse_pcap_frame_be, parse_pcap_frame_modified, parse_pcap_header, parse_sectionheaderblock,
};

use crate::Format;
use crate::error::{CaptureError, SkipReason, Skipped};
use crate::link::Link;

/// One UDP datagram's payload and when it was captured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Datagram<'a> {
    /// Capture time since 1970-01-01T00:00:00 UTC (`None` for a pcapng simple packet
    /// block, which has none).
    pub time: Option<Duration>,
    /// The UDP payload.
    pub payload: &'a [u8],
    /// Index of its packet among the file's packet records (0-based).
    pub packet: usize,
}

/// What a capture holds: its UDP datagrams in file order and the packets skipped.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Capture<'a> {
    /// [`Format::Pcap`] or [`Format::PcapNg`].
    pub format: Format,
    /// The UDP payloads.
    pub datagrams: Vec<Datagram<'a>>,
    /// Packets that gave none, each with its reason.
    pub skipped: Vec<Skipped>,
    /// Packet records seen (datagrams + skipped packets; a truncated tail counts one).
    pub packets: usize,
}

/// Reads a pcap or pcapng capture held in memory (the format by its magic).
///
/// # Errors
/// [`CaptureError::NotACapture`] when `bytes` has neither magic,
/// [`CaptureError::BadHeader`] when the file header cannot be parsed,
/// [`CaptureError::UnsupportedLinkType`] for a pcap file of a link type without IP.
pub fn read(bytes: &[u8]) -> Result<Capture<'_>, CaptureError> {
    match Format::sniff(bytes) {
        Format::Pcap => read_pcap(bytes),
        Format::PcapNg => read_pcapng(bytes),
        Format::Other => Err(CaptureError::NotACapture {
            first: bytes.iter().take(4).copied().collect(),
        }),
    }
}

fn new_capture(format: Format) -> Capture<'static> {
    Capture {
        format,
        datagrams: Vec::new(),
        skipped: Vec::new(),
        packets: 0,
    }
}

impl<'a> Capture<'a> {
    /// One packet record: its UDP payload, or the reason it has none.
    fn take(
        &mut self,
        offset: usize,
        time: Result<Option<Duration>, SkipReason>,
        payload: Result<&'a [u8], SkipReason>,
    ) {
        let packet = self.packets;
        self.packets += 1;
        match time.and_then(|t| payload.map(|p| (t, p))) {
            Ok((time, payload)) => self.datagrams.push(Datagram {
                time,
                payload,
                packet,
            }),
            Err(reason) => self.skipped.push(Skipped {
                packet,
                offset,
                reason,
            }),
        }
    }

    /// The file ends inside a record or block.
    fn truncated(&mut self, offset: usize, what: &'static str, have: usize) {
        let packet = self.packets;
        self.packets += 1;
        self.skipped.push(Skipped {
            packet,
            offset,
            reason: SkipReason::Truncated { what, have },
        });
    }
}

fn header_error<E: std::fmt::Debug>(format: &'static str, e: &E) -> CaptureError {
    CaptureError::BadHeader {
        format,
        what: format!("{e:?}"),
    }
}

/// A pcap file: global header, then records (`ts_sec, ts_usec|ts_nsec, caplen, len`).
fn read_pcap(bytes: &[u8]) -> Result<Capture<'_>, CaptureError> {
    let (rest, header) = parse_pcap_header(bytes).map_err(|e| header_error("pcap", &e))?;
    let linktype = header.network.0;
    let link = Link::of(linktype).ok_or(CaptureError::UnsupportedLinkType { linktype })?;
    let nanos = header.is_nanosecond_precision();
    let parse: fn(&[u8]) -> nom_result::Frame<'_> = if header.is_modified_format() {
        parse_pcap_frame_modified
    } else if header.is_bigendian() {
        parse_pcap_frame_be
    } else {
        parse_pcap_frame
    };
    let mut out = new_capture(Format::Pcap);
    let mut rest = rest;
    while !rest.is_empty() {
        let offset = bytes.len() - rest.len();
        match parse(rest) {
            Ok((next, frame)) => {
                let sub = u64::from(frame.ts_usec) * if nanos { 1 } else { 1000 };
                let time = Duration::from_secs(u64::from(frame.ts_sec)) + Duration::from_nanos(sub);
                out.take(offset, Ok(Some(time)), link.udp_payload(frame.data));
                rest = next;
            }
            Err(_) => {
                out.truncated(offset, "pcap record", rest.len());
                break;
            }
        }
    }
    Ok(out)
}

mod nom_result {
    use super::{LegacyPcapBlock, PcapError};
    /// What the pcap frame parsers return.
    pub(super) type Frame<'a> =
        pcap_parser::nom::IResult<&'a [u8], LegacyPcapBlock<'a>, PcapError<&'a [u8]>>;
}

/// A described pcapng interface.
struct Interface {
    linktype: i32,
    link: Option<Link>,
    /// Timestamp units per second (`None`: the `if_tsresol` option is out of range).
    resolution: Option<u64>,
    /// Seconds added to every timestamp (`if_tsoffset`).
    offset: i64,
}

impl Interface {
    /// An enhanced packet block's time.
    fn time(&self, high: u32, low: u32) -> Result<Option<Duration>, SkipReason> {
        let res = self
            .resolution
            .filter(|r| *r > 0)
            .ok_or(SkipReason::Timestamp)?;
        let ts = (u64::from(high) << 32) | u64::from(low);
        let secs = i128::from(ts / res) + i128::from(self.offset);
        let frac = u128::from(ts % res) * 1_000_000_000 / u128::from(res);
        let secs = u64::try_from(secs).map_err(|_| SkipReason::Timestamp)?;
        let nanos = u32::try_from(frac).map_err(|_| SkipReason::Timestamp)?;
        Ok(Some(Duration::new(secs, nanos)))
    }
}

/// A pcapng file: sections of blocks; each section's interfaces (with their link
/// types and timestamp resolutions) and its byte order.
fn read_pcapng(bytes: &[u8]) -> Result<Capture<'_>, CaptureError> {
    let (_, shb) = parse_sectionheaderblock(bytes).map_err(|e| header_error("pcapng", &e))?;
    let mut big_endian = shb.big_endian();
    let mut interfaces: Vec<Interface> = Vec::new();
    let mut out = new_capture(Format::PcapNg);
    let mut rest = bytes;
    while !rest.is_empty() {
        let offset = bytes.len() - rest.len();
        let parsed = if rest.starts_with(&[0x0a, 0x0d, 0x0d, 0x0a]) {
            parse_sectionheaderblock(rest).map(|(r, b)| (r, Block::SectionHeader(b)))
        } else if big_endian {
            parse_block_be(rest)
        } else {
            parse_block_le(rest)
        };
        let (next, block) = match parsed {
            Ok(ok) => ok,
            Err(nom::Err::Incomplete(_)) => {
                out.truncated(offset, "pcapng block", rest.len());
                break;
            }
            Err(_) => {
                let packet = out.packets;
                out.packets += 1;
                out.skipped.push(Skipped {
                    packet,
                    offset,
                    reason: SkipReason::BadBlock,
                });
                break;
            }
        };
        match block {
            Block::SectionHeader(s) => {
                big_endian = s.big_endian();
                interfaces.clear();
            }
            Block::InterfaceDescription(idb) => interfaces.push(Interface {
                linktype: idb.linktype.0,
                link: Link::of(idb.linktype.0),
                resolution: idb.ts_resolution(),
                offset: idb.ts_offset(),
            }),
            Block::EnhancedPacket(epb) => {
                // The block's data is padded to 32 bits: the packet is its first caplen bytes.
                let data = head(epb.data, epb.caplen);
                let (time, payload) = on_interface(&interfaces, epb.if_id, |i, link| {
                    (i.time(epb.ts_high, epb.ts_low), link.udp_payload(data))
                });
                out.take(offset, time, payload);
            }
            Block::SimplePacket(spb) => {
                // A simple packet block's packet is its original length, padded.
                let data = head(spb.data, spb.origlen);
                let (time, payload) =
                    on_interface(&interfaces, 0, |_, link| (Ok(None), link.udp_payload(data)));
                out.take(offset, time, payload);
            }
            _ => {}
        }
        rest = next;
    }
    Ok(out)
}

/// The first `len` bytes of `data` (all of it when shorter).
fn head(data: &[u8], len: u32) -> &[u8] {
    let n = usize::try_from(len).map_or(data.len(), |n| n.min(data.len()));
    &data[..n]
}

type Taken<'a> = (
    Result<Option<Duration>, SkipReason>,
    Result<&'a [u8], SkipReason>,
);

/// Runs `f` on interface `id` if it is described and its link type supported.
fn on_interface<'a>(
    interfaces: &[Interface],
    id: u32,
    f: impl FnOnce(&Interface, Link) -> Taken<'a>,
) -> Taken<'a> {
    let found = usize::try_from(id).ok().and_then(|i| interfaces.get(i));
    match found {
        None => (
            Err(SkipReason::UnknownInterface { interface: id }),
            Err(SkipReason::NotIp),
        ),
        Some(i) => match i.link {
            Some(link) => f(i, link),
            None => (
                Err(SkipReason::LinkType {
                    interface: id,
                    linktype: i.linktype,
                }),
                Err(SkipReason::NotIp),
            ),
        },
    }
}
