"""The hand-over between the UI and the render thread keeps only the latest request."""

import threading

from biceps.tui.latest_only import LatestOnly


def test_a_new_item_replaces_one_not_yet_taken():
    box = LatestOnly()
    for item in range(5):
        box.put(item)
    assert box.take() == 4


def test_the_next_item_waits_until_the_last_one_is_done():
    box = LatestOnly()
    box.put("first")
    assert box.take() == "first"
    box.put("second")
    taken = []
    worker = threading.Thread(target=lambda: taken.append(box.take()))
    worker.start()
    worker.join(0.05)
    assert taken == []  # the first one's result has not been used yet
    box.done()
    worker.join()
    assert taken == ["second"]


def test_closing_releases_a_waiting_worker():
    box = LatestOnly()
    taken = []
    worker = threading.Thread(target=lambda: taken.append(box.take()))
    worker.start()
    box.close()
    worker.join()
    assert taken == [None]
