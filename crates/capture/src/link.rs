//! From a captured frame to its UDP payload, by the capture's link type.

use etherparse::{NetSlice, SlicedPacket, TransportSlice};

use crate::error::SkipReason;

/// The link types read: the frame parser for each.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Link {
    /// LINKTYPE_ETHERNET (1).
    Ethernet,
    /// LINKTYPE_RAW (101), LINKTYPE_IPV4 (228), LINKTYPE_IPV6 (229).
    RawIp,
    /// LINKTYPE_LINUX_SLL (113).
    LinuxSll,
}

impl Link {
    /// The link of a pcap / pcapng link type, if supported.
    pub(crate) fn of(linktype: i32) -> Option<Self> {
        match linktype {
            1 => Some(Self::Ethernet),
            101 | 228 | 229 => Some(Self::RawIp),
            113 => Some(Self::LinuxSll),
            _ => None,
        }
    }

    /// The UDP payload of `frame`.
    pub(crate) fn udp_payload(self, frame: &[u8]) -> Result<&[u8], SkipReason> {
        let sliced = match self {
            Self::Ethernet => SlicedPacket::from_ethernet(frame),
            Self::RawIp => SlicedPacket::from_ip(frame),
            Self::LinuxSll => SlicedPacket::from_linux_sll(frame),
        }
        .map_err(|e| SkipReason::Malformed {
            what: e.to_string(),
        })?;
        let protocol = match &sliced.net {
            Some(NetSlice::Ipv4(ip)) => {
                if ip.is_payload_fragmented() {
                    return Err(SkipReason::Fragment);
                }
                ip.payload_ip_number().0
            }
            Some(NetSlice::Ipv6(ip)) => {
                if ip.is_payload_fragmented() {
                    return Err(SkipReason::Fragment);
                }
                ip.payload().ip_number.0
            }
            _ => return Err(SkipReason::NotIp),
        };
        match sliced.transport {
            Some(TransportSlice::Udp(udp)) => Ok(udp.payload()),
            _ => Err(SkipReason::NotUdp { protocol }),
        }
    }
}
