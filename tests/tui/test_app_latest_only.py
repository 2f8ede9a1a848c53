"""The hand-over between the UI and the render thread keeps only the latest request, and
hands results over one at a time."""

import threading

from biceps.tui.latest_only import LatestOnly


def _in_a_thread(call) -> tuple[threading.Thread, list]:
    """``call()`` running in a thread of its own, and the list its result will be put in."""
    results: list = []
    worker = threading.Thread(target=lambda: results.append(call()))
    worker.start()
    return worker, results


def test_a_new_item_replaces_one_not_yet_taken():
    box = LatestOnly()
    for item in range(5):
        box.put(item)
    assert box.take() == 4


def test_the_next_item_is_taken_while_the_last_result_is_in_use():
    box = LatestOnly()
    box.put("first")
    assert box.take() == "first"
    assert box.hand_over()
    box.put("second")
    assert box.take() == "second"  # to work on ahead: the UI is not done with "first"


def test_the_next_result_waits_until_the_last_one_is_done():
    box = LatestOnly()
    assert box.hand_over()
    worker, handed = _in_a_thread(box.hand_over)
    worker.join(0.05)
    assert handed == []  # the first result has not been used yet
    box.done()
    worker.join()
    assert handed == [True]


def test_newer_takes_only_what_was_put_since_without_waiting():
    box = LatestOnly()
    box.put("first")
    box.take()
    assert box.newer() is None
    box.put("second")
    box.put("third")
    assert box.newer() == "third"
    assert box.newer() is None


def test_closing_releases_a_waiting_worker():
    box = LatestOnly()
    worker, taken = _in_a_thread(box.take)
    box.close()
    worker.join()
    assert taken == [None]


def test_closing_releases_a_worker_waiting_to_hand_over():
    box = LatestOnly()
    assert box.hand_over()
    worker, handed = _in_a_thread(box.hand_over)
    box.close()
    worker.join()
    assert handed == [False]
