"""Pure-Python reader for LCM log files (the format lcm-logger writes).

Debian 12 has no python3-lcm, so this reads the file format directly: each
event is a 28-byte big-endian header (sync word 0xEDA1DA01, event number,
utime in us, channel length, data length), the channel name and the data.
Errors name the file and the byte offset.
"""

import struct
from typing import Iterator, NamedTuple

_SYNC = 0xEDA1DA01
_HEADER = struct.Struct(">IqqII")
MAX_CHANNEL_BYTES = 256  # LCM's own limit on channel names
MAX_EVENT_BYTES = 1 << 28  # an event larger than this is a corrupt header, not data


class LogError(Exception):
    """A log file that is unreadable, truncated or corrupt."""


class Event(NamedTuple):
    event_number: int
    utime: int  # us, when the event was recorded
    channel: str
    data: bytes


def read_events(path: str) -> Iterator[Event]:
    """Yields the events of the log at `path` in order.

    Raises LogError naming the file when it cannot be opened or when it ends
    inside an event or loses the sync word (a truncated or corrupt log)."""
    try:
        f = open(path, "rb")
    except OSError as e:
        raise LogError(f"{path}: cannot open: {e.strerror}") from None
    with f:
        offset = 0
        while True:
            header = f.read(_HEADER.size)
            if not header:
                return
            if len(header) < _HEADER.size:
                raise LogError(f"{path}: truncated at byte {offset} (inside an event header)")
            sync, number, utime, channel_len, data_len = _HEADER.unpack(header)
            if sync != _SYNC:
                raise LogError(f"{path}: corrupt at byte {offset} (no sync word 0xEDA1DA01: not an LCM log?)")
            if channel_len > MAX_CHANNEL_BYTES or data_len > MAX_EVENT_BYTES:
                raise LogError(f"{path}: corrupt at byte {offset} (channel {channel_len} B, data {data_len} B)")
            channel = f.read(channel_len)
            data = f.read(data_len)
            if len(channel) < channel_len or len(data) < data_len:
                raise LogError(f"{path}: truncated at byte {offset} (event {number} ends past the file)")
            offset += _HEADER.size + channel_len + data_len
            yield Event(number, utime, channel.decode("utf-8", "replace"), data)
