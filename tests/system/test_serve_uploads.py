"""Uploads to ``biceps serve`` from outside, as the page sends them: each page's token writes
into its own visitor's folder and no other, only while that visitor is there; bad names,
files that are not models and files too large are refused with the reason, and nothing is
written anywhere else."""

from __future__ import annotations

import asyncio
import re
from pathlib import Path
from urllib.parse import quote

import pytest

from biceps.engine.config import BUNDLED, DEFAULT_CONFIG, LARGEST_FILE
from browser import served

pytest.importorskip("aiohttp", reason="comes with textual-serve, the serve extra")
import aiohttp  # noqa: E402

MODEL = (BUNDLED / "toy.toml").read_bytes()
PAGE_ADDRESS = re.compile(r'data-session-websocket-url="([^"]+)"')
UPLOAD_ADDRESS = re.compile(r'data-upload-url="([^"]+)"')


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """A server, and its scratch folder (where each visitor's folder is made), in a
    temporary folder of its own, where no other server's are."""
    temporary = tmp_path_factory.mktemp("server")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("TMPDIR", str(temporary))
        with served(DEFAULT_CONFIG) as url:
            (scratch,) = temporary.glob("biceps-serve-*")
            yield url, scratch


def _tree(root: Path) -> dict[str, bytes | None]:
    return {str(path.relative_to(root)): path.read_bytes() if path.is_file() else None
            for path in root.rglob("*")}


class Visitor:
    """A page loaded, and its websocket open (the app's process starting): its upload
    address and its folder."""

    def __init__(self, session: aiohttp.ClientSession, url: str, scratch: Path) -> None:
        self.session, self.url, self.scratch = session, url, scratch

    async def __aenter__(self) -> Visitor:
        before = set(self.scratch.glob("visitor-*"))
        async with self.session.get(self.url) as response:
            page = await response.text()
        self.socket_url = PAGE_ADDRESS.search(page)[1]
        self.upload_url = UPLOAD_ADDRESS.search(page)[1]
        self.socket = await self.session.ws_connect(self.socket_url + "?width=80&height=24")
        for _ in range(100):
            made = set(self.scratch.glob("visitor-*")) - before
            if made:
                (self.folder,) = made
                return self
            await asyncio.sleep(0.1)
        raise AssertionError("the visitor's folder was never made")

    async def __aexit__(self, *exception) -> None:
        await self.socket.close()


async def _upload(session, address: str, name: str, data) -> tuple[int, str]:
    async with session.post(address, data=data,
                            headers={"X-File-Name": quote(name, safe="")}) as response:
        return response.status, await response.text()


def test_an_upload_goes_into_its_own_visitors_folder_and_no_other(server):
    url, scratch = server

    async def visit() -> None:
        async with aiohttp.ClientSession() as session:
            async with Visitor(session, url, scratch) as one, Visitor(session, url,
                                                                      scratch) as other:
                status, said = await _upload(session, one.upload_url, "mine.toml", MODEL)
                assert (status, said) == (200, "mine.toml is in your folder: open it in the "
                                          "app with ctrl+o")
                assert (one.folder / "mine.toml").read_bytes() == MODEL
                assert not (other.folder / "mine.toml").exists()
                status, said = await _upload(session, other.upload_url, "mine.toml", b"# b\n")
                assert status == 200
                assert (other.folder / "mine.toml").read_bytes() == b"# b\n"
                assert (one.folder / "mine.toml").read_bytes() == MODEL
                status, said = await _upload(session, one.upload_url, "mine.toml", b"# again\n")
                assert status == 200 and "replacing the earlier one" in said

    asyncio.run(visit())


def _chunks(size: int):
    async def chunks():
        for _ in range(size // 65536 + 1):
            yield b"#" * 65536
    return chunks()


@pytest.mark.parametrize("name, data, status, reason", [
    ("../mine.toml", MODEL, 400, "send a file's name, not a path"),
    ("/tmp/mine.toml", MODEL, 400, "send a file's name, not a path"),
    ("..", MODEL, 400, "may not start with '.'"),
    ("mine\n.toml", MODEL, 400, "control characters"),
    ("picture.png", b"\x89PNG", 400, "picture.png is not a model"),
    ("mine.toml", b"\x89PNG\r\n\x1a\n", 400, "mine.toml is not a model: it is not a text file"),
    ("big.toml", b"#" * (LARGEST_FILE + 1), 413, "larger than 1 MiB"),
    ("chunked.toml", "chunks", 413, "larger than 1 MiB"),  # no length said beforehand
])
def test_bad_uploads_are_refused_with_the_reason_and_write_nothing(server, name, data, status,
                                                                   reason):
    url, scratch = server

    async def visit() -> tuple[int, str, dict, dict]:
        async with aiohttp.ClientSession() as session:
            async with Visitor(session, url, scratch) as visitor:
                before = _tree(scratch)
                body = _chunks(4 * LARGEST_FILE) if data == "chunks" else data
                answer = await _upload(session, visitor.upload_url, name, body)
                return (*answer, before, _tree(scratch))

    got, said, before, after = asyncio.run(visit())
    assert got == status
    assert said.startswith("Not uploaded: ") and reason in said
    # Nothing new or changed (earlier tests' visitors' folders may go meanwhile).
    assert {path for path, data in after.items()
            if path not in before or before[path] != data} == set()


def test_a_link_in_the_folder_is_not_written_through(server, tmp_path):
    url, scratch = server
    secret = tmp_path / "secret.toml"
    secret.write_bytes(b"# the server's\n")

    async def visit() -> tuple[int, str]:
        async with aiohttp.ClientSession() as session:
            async with Visitor(session, url, scratch) as visitor:
                (visitor.folder / "link.toml").symlink_to(secret)
                return await _upload(session, visitor.upload_url, "link.toml", MODEL)

    status, said = asyncio.run(visit())
    assert status == 400 and "is not a file" in said
    assert secret.read_bytes() == b"# the server's\n"


def test_a_token_uploads_only_while_its_visitor_is_there(server):
    url, scratch = server

    async def visit() -> None:
        async with aiohttp.ClientSession() as session:
            async with session.get(url) as response:
                unused = UPLOAD_ADDRESS.search(await response.text())[1]
            made_up = unused.rsplit("/", 1)[0] + "/" + "A" * 43
            async with Visitor(session, url, scratch) as visitor:
                for address in (unused, made_up):  # a page not yet connected, no page
                    status, said = await _upload(session, address, "mine.toml", MODEL)
                    assert status == 403 and "reload the page" in said
                # One websocket a page: another with its token is turned away.
                async with session.ws_connect(visitor.socket_url) as again:
                    message = await asyncio.wait_for(again.receive(), 30)
                    assert b"out of date" in message.data
                address = visitor.upload_url
                assert (await _upload(session, address, "mine.toml", MODEL))[0] == 200
            # Gone from the server's list once its websocket closes, before its process ends
            for _ in range(300):
                status, said = await _upload(session, address, "late.toml", MODEL)
                if status != 200:
                    break
                await asyncio.sleep(0.1)
            assert status == 403 and "this page's visit has ended" in said

    asyncio.run(visit())
