"""The terminal's flow control is off while the app runs, and its mode restored after
(tui/flow_control.py)."""

import os
import select
import termios

import pytest

from biceps.tui.flow_control import no_flow_control


def _readable(fd: int) -> bytes:
    data = b""
    while select.select([fd], [], [], 0.2)[0]:
        data += os.read(fd, 1 << 16)
    return data


def _type(master: int, slave: int, key: bytes) -> None:
    """Type ``key`` and a newline, and wait until the terminal has read them."""
    os.write(master, key + b"\n")
    assert select.select([slave], [], [], 5)[0]
    os.read(slave, 1 << 16)


def test_a_ctrl_s_is_input_within_and_the_mode_is_as_it_was_after():
    master, slave = os.openpty()
    try:
        mode = termios.tcgetattr(slave)
        mode[3] &= ~termios.ECHO  # what is typed is not written back: only output is read
        termios.tcsetattr(slave, termios.TCSANOW, mode)
        before = termios.tcgetattr(slave)
        assert before[0] & termios.IXON  # a terminal's default: ctrl+s stops its output
        os.set_blocking(slave, False)  # a write that would wait for a ctrl+q raises
        with no_flow_control(slave):
            _type(master, slave, b"\x13")  # ctrl+s
            os.write(slave, b"still written")
            assert _readable(master) == b"still written"
            os.write(master, b"typed for the app\n")
            assert select.select([slave], [], [], 5)[0]  # there to be read
        assert termios.tcgetattr(slave) == before
        assert not select.select([slave], [], [], 0.2)[0]  # what the app never read: dropped
        _type(master, slave, b"\x13")  # flow control is the terminal's again
        with pytest.raises(BlockingIOError):
            os.write(slave, b"held")
    finally:
        os.close(master)
        os.close(slave)


def test_where_there_is_no_terminal_nothing_changes(tmp_path):
    with open(tmp_path / "file", "w") as file, no_flow_control(file.fileno()):
        pass
