//! Reading and writing captures: the round trip, and every bad-input path (truncated
//! files, link types without IP, packets that are not UDP, fragments, malformed
//! headers, pcapng interfaces) skipped with its typed reason or refused whole.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Duration;

use argus_capture::{CaptureError, Datagram, Endpoints, Format, SkipReason, read, write_pcap};
use etherparse::PacketBuilder;

const MAC: [u8; 6] = [2, 0, 0, 0, 0, 1];

fn udp_frame(payload: &[u8]) -> Vec<u8> {
    let b = PacketBuilder::ethernet2(MAC, MAC)
        .ipv4([10, 0, 0, 1], [10, 0, 0, 2], 64)
        .udp(1, 2);
    let mut v = Vec::new();
    b.write(&mut v, payload).unwrap();
    v
}

fn tcp_frame() -> Vec<u8> {
    let b = PacketBuilder::ethernet2(MAC, MAC)
        .ipv4([10, 0, 0, 1], [10, 0, 0, 2], 64)
        .tcp(1, 2, 0, 1000);
    let mut v = Vec::new();
    b.write(&mut v, &[1, 2, 3]).unwrap();
    v
}

/// A little-endian microsecond pcap file of `frames` on `linktype`, by hand.
fn pcap(linktype: u32, frames: &[Vec<u8>]) -> Vec<u8> {
    let mut v = Vec::new();
    v.extend(0xa1b2_c3d4u32.to_le_bytes());
    v.extend(2u16.to_le_bytes());
    v.extend(4u16.to_le_bytes());
    v.extend([0; 8]);
    v.extend(65535u32.to_le_bytes());
    v.extend(linktype.to_le_bytes());
    for (k, f) in frames.iter().enumerate() {
        v.extend(u32::try_from(k).unwrap().to_le_bytes());
        v.extend(250_000u32.to_le_bytes());
        let n = u32::try_from(f.len()).unwrap();
        v.extend(n.to_le_bytes());
        v.extend(n.to_le_bytes());
        v.extend(f);
    }
    v
}

fn block(kind: u32, body: &[u8]) -> Vec<u8> {
    let mut body = body.to_vec();
    while !body.len().is_multiple_of(4) {
        body.push(0);
    }
    let len = u32::try_from(body.len() + 12).unwrap();
    let mut v = Vec::new();
    v.extend(kind.to_le_bytes());
    v.extend(len.to_le_bytes());
    v.extend(body);
    v.extend(len.to_le_bytes());
    v
}

fn shb() -> Vec<u8> {
    let mut b = Vec::new();
    b.extend(0x1a2b_3c4du32.to_le_bytes());
    b.extend(1u16.to_le_bytes());
    b.extend(0u16.to_le_bytes());
    b.extend((-1i64).to_le_bytes());
    block(0x0a0d_0d0a, &b)
}

fn idb(linktype: u16) -> Vec<u8> {
    let mut b = Vec::new();
    b.extend(linktype.to_le_bytes());
    b.extend(0u16.to_le_bytes());
    b.extend(0u32.to_le_bytes());
    block(1, &b)
}

/// An enhanced packet block on `interface` at `ts` microseconds (the default resolution).
fn epb(interface: u32, ts: u64, frame: &[u8]) -> Vec<u8> {
    let mut b = Vec::new();
    b.extend(interface.to_le_bytes());
    b.extend(u32::try_from(ts >> 32).unwrap().to_le_bytes());
    b.extend(u32::try_from(ts & 0xffff_ffff).unwrap().to_le_bytes());
    let n = u32::try_from(frame.len()).unwrap();
    b.extend(n.to_le_bytes());
    b.extend(n.to_le_bytes());
    b.extend(frame);
    block(6, &b)
}

#[test]
fn written_pcap_reads_back_exactly() {
    let payloads: Vec<Vec<u8>> = (0..5u8).map(|k| vec![k; 10 + usize::from(k)]).collect();
    let datagrams: Vec<Datagram<'_>> = payloads
        .iter()
        .enumerate()
        .map(|(k, p)| Datagram {
            // Microseconds: what pcap holds, so the time comes back exactly.
            time: Some(Duration::new(1_633_613_580 + k as u64, 123_456_000)),
            payload: p,
            packet: k,
        })
        .collect();
    let bytes = write_pcap(&datagrams, &Endpoints::default()).unwrap();
    assert_eq!(Format::sniff(&bytes), Format::Pcap);
    let back = read(&bytes).unwrap();
    assert_eq!(back.format, Format::Pcap);
    assert!(back.skipped.is_empty());
    assert_eq!(back.datagrams, datagrams);
    assert_eq!(back.packets, 5);
    // Too long for one IPv4/UDP packet: a typed error, not a wrapped length.
    let big = vec![0u8; argus_capture::MAX_PAYLOAD + 1];
    let d = Datagram {
        time: None,
        payload: &big,
        packet: 0,
    };
    assert!(matches!(
        write_pcap(&[d], &Endpoints::default()),
        Err(CaptureError::Write { packet: 0, .. })
    ));
}

#[test]
fn truncated_pcap_keeps_the_whole_records() {
    let bytes = pcap(1, &[udp_frame(b"one"), udp_frame(b"two")]);
    // Cut inside the second record's data: the first is kept, the tail counted.
    let cut = &bytes[..bytes.len() - 3];
    let c = read(cut).unwrap();
    assert_eq!(c.datagrams.len(), 1);
    assert_eq!(c.datagrams[0].payload, b"one");
    assert_eq!(c.datagrams[0].time, Some(Duration::new(0, 250_000_000)));
    assert_eq!(c.skipped.len(), 1);
    let s = &c.skipped[0];
    assert_eq!((s.packet, s.offset), (1, 24 + 16 + udp_frame(b"one").len()));
    assert!(matches!(
        s.reason,
        SkipReason::Truncated {
            what: "pcap record",
            ..
        }
    ));
    // Cut inside a record header too.
    let c = read(&bytes[..24 + 7]).unwrap();
    assert!(c.datagrams.is_empty());
    assert!(matches!(
        c.skipped[0].reason,
        SkipReason::Truncated { have: 7, .. }
    ));
    // Cut inside the global header: nothing is readable.
    assert!(matches!(
        read(&bytes[..10]),
        Err(CaptureError::BadHeader { format: "pcap", .. })
    ));
}

#[test]
fn link_types_without_ip_are_refused() {
    // 105: IEEE 802.11.
    let bytes = pcap(105, &[udp_frame(b"x")]);
    assert_eq!(
        read(&bytes),
        Err(CaptureError::UnsupportedLinkType { linktype: 105 })
    );
    // Raw IP (101) is read: the frame without its 14-byte Ethernet header.
    let f = udp_frame(b"raw");
    let raw = pcap(101, &[f[14..].to_vec()]);
    let c = read(&raw).unwrap();
    assert_eq!(c.datagrams[0].payload, b"raw");
}

#[test]
fn packets_that_are_not_whole_udp_are_skipped_with_their_reason() {
    let mut fragment = udp_frame(b"frag");
    // IPv4 flags/fragment offset (bytes 20–21 of the frame): more fragments.
    fragment[20] |= 0x20;
    let mut arp = udp_frame(b"x");
    arp[12..14].copy_from_slice(&0x0806u16.to_be_bytes());
    let short = udp_frame(b"cut")[..20].to_vec();
    let frames = [tcp_frame(), fragment, arp, short, udp_frame(b"ok")];
    let bytes = pcap(1, &frames);
    let c = read(&bytes).unwrap();
    assert_eq!(c.datagrams.len(), 1);
    assert_eq!(
        (c.datagrams[0].payload, c.datagrams[0].packet),
        (&b"ok"[..], 4)
    );
    let reasons: Vec<&SkipReason> = c.skipped.iter().map(|s| &s.reason).collect();
    assert_eq!(reasons[0], &SkipReason::NotUdp { protocol: 6 });
    assert_eq!(reasons[1], &SkipReason::Fragment);
    assert!(
        matches!(reasons[2], SkipReason::NotIp | SkipReason::Malformed { .. }),
        "{reasons:?}"
    );
    assert!(
        matches!(reasons[3], SkipReason::Malformed { .. }),
        "{reasons:?}"
    );
    assert_eq!(c.packets, 5);
}

#[test]
fn pcapng_interfaces_times_and_bad_blocks() {
    let mut bytes = shb();
    bytes.extend(idb(1));
    bytes.extend(idb(105));
    bytes.extend(epb(0, 1_500_000, &udp_frame(b"a")));
    bytes.extend(epb(1, 2_000_000, &udp_frame(b"b")));
    bytes.extend(epb(7, 2_500_000, &udp_frame(b"c")));
    bytes.extend(epb(0, 3_000_000, &tcp_frame()));
    assert_eq!(Format::sniff(&bytes), Format::PcapNg);
    let c = read(&bytes).unwrap();
    assert_eq!(c.format, Format::PcapNg);
    assert_eq!(c.datagrams.len(), 1);
    // 1 500 000 µs (the default resolution 10^-6).
    assert_eq!(c.datagrams[0].time, Some(Duration::from_millis(1500)));
    assert_eq!(c.datagrams[0].payload, b"a");
    let reasons: Vec<SkipReason> = c.skipped.iter().map(|s| s.reason.clone()).collect();
    assert_eq!(
        reasons,
        vec![
            SkipReason::LinkType {
                interface: 1,
                linktype: 105
            },
            SkipReason::UnknownInterface { interface: 7 },
            SkipReason::NotUdp { protocol: 6 },
        ]
    );
    // A truncated last block: counted, the rest kept.
    let mut cut = shb();
    cut.extend(idb(1));
    cut.extend(epb(0, 1, &udp_frame(b"a")));
    let whole = cut.len();
    cut.extend(&epb(0, 2, &udp_frame(b"b"))[..20]);
    let c = read(&cut).unwrap();
    assert_eq!(c.datagrams.len(), 1);
    assert_eq!(c.skipped[0].offset, whole);
    assert!(matches!(
        c.skipped[0].reason,
        SkipReason::Truncated {
            what: "pcapng block",
            ..
        }
    ));
    // A block whose trailing length disagrees: unparsable, the rest of the file lost.
    let mut bad = shb();
    bad.extend(idb(1));
    let mut b = epb(0, 1, &udp_frame(b"a"));
    let n = b.len();
    b[n - 4] ^= 0x40;
    bad.extend(b);
    bad.extend(epb(0, 2, &udp_frame(b"b")));
    let c = read(&bad).unwrap();
    assert!(c.datagrams.is_empty());
    assert_eq!(c.skipped.len(), 1);
    // A header that is not a section header block: refused whole.
    assert!(matches!(
        read(&shb()[..8]),
        Err(CaptureError::BadHeader {
            format: "pcapng",
            ..
        })
    ));
}

#[test]
fn other_content_is_not_a_capture() {
    let asterix = [48u8, 0, 3];
    assert_eq!(Format::sniff(&asterix), Format::Other);
    assert_eq!(
        read(&asterix),
        Err(CaptureError::NotACapture {
            first: vec![48, 0, 3]
        })
    );
    assert_eq!(Format::sniff(&[]), Format::Other);
}
