//! Writing UDP payloads as a pcap file: Ethernet II / IPv4 / UDP frames (built by
//! etherparse), microsecond timestamps, little-endian (the common `a1b2c3d4` layout).

use etherparse::PacketBuilder;
use pcap_parser::{LegacyPcapBlock, Linktype, PcapHeader, ToVec};

use crate::error::CaptureError;
use crate::read::Datagram;

/// The addresses the written frames carry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Endpoints {
    /// Source MAC.
    pub src_mac: [u8; 6],
    /// Destination MAC.
    pub dst_mac: [u8; 6],
    /// Source IPv4 address.
    pub src_ip: [u8; 4],
    /// Destination IPv4 address.
    pub dst_ip: [u8; 4],
    /// Source UDP port.
    pub src_port: u16,
    /// Destination UDP port.
    pub dst_port: u16,
}

impl Default for Endpoints {
    /// A radar head sending to a multicast group, as surveillance networks do:
    /// 10.0.0.1:50000 → 239.0.0.1:8600 (MAC 01:00:5e:00:00:01, the group's).
    fn default() -> Self {
        Self {
            src_mac: [0x02, 0, 0, 0, 0, 0x01],
            dst_mac: [0x01, 0x00, 0x5e, 0x00, 0x00, 0x01],
            src_ip: [10, 0, 0, 1],
            dst_ip: [239, 0, 0, 1],
            src_port: 50000,
            dst_port: 8600,
        }
    }
}

/// The largest UDP payload of one IPv4 packet: 65 535 − 20 (IPv4) − 8 (UDP).
pub const MAX_PAYLOAD: usize = 65_507;

/// A pcap file (Ethernet link type) holding each datagram as one IPv4/UDP packet from
/// `endpoints`, at its time (`None` is written as 0).
///
/// # Errors
/// [`CaptureError::Write`] for a payload over [`MAX_PAYLOAD`] bytes or a time past
/// 2106 (pcap's 32-bit seconds).
pub fn write_pcap(
    datagrams: &[Datagram<'_>],
    endpoints: &Endpoints,
) -> Result<Vec<u8>, CaptureError> {
    let header = PcapHeader {
        snaplen: 65_535,
        network: Linktype::ETHERNET,
        ..PcapHeader::new()
    };
    let mut out = header.to_vec_raw().map_err(|e| write_error(0, &e))?;
    for (k, d) in datagrams.iter().enumerate() {
        if d.payload.len() > MAX_PAYLOAD {
            return Err(CaptureError::Write {
                packet: k,
                what: format!(
                    "{} bytes exceed one UDP/IPv4 payload ({MAX_PAYLOAD})",
                    d.payload.len()
                ),
            });
        }
        let time = d.time.unwrap_or_default();
        let ts_sec = u32::try_from(time.as_secs()).map_err(|_| CaptureError::Write {
            packet: k,
            what: format!("time {} s is past pcap's 32-bit seconds", time.as_secs()),
        })?;
        let builder = PacketBuilder::ethernet2(endpoints.src_mac, endpoints.dst_mac)
            .ipv4(endpoints.src_ip, endpoints.dst_ip, 64)
            .udp(endpoints.src_port, endpoints.dst_port);
        let mut frame = Vec::with_capacity(builder.size(d.payload.len()));
        builder
            .write(&mut frame, d.payload)
            .map_err(|e| write_error(k, &e))?;
        let len = u32::try_from(frame.len()).map_err(|_| write_error(k, &"frame length"))?;
        let block = LegacyPcapBlock {
            ts_sec,
            ts_usec: time.subsec_micros(),
            caplen: len,
            origlen: len,
            data: &frame,
        };
        out.extend(block.to_vec_raw().map_err(|e| write_error(k, &e))?);
    }
    Ok(out)
}

fn write_error<E: std::fmt::Debug>(packet: usize, e: &E) -> CaptureError {
    CaptureError::Write {
        packet,
        what: format!("{e:?}"),
    }
}
