"""ladarsim.Campaign: a campaign the command line rendered, its sequences in the index's order and
by split, each one's dataset read as its files, its returns by class recounted from its frames."""
import numpy as np
import pytest

import ladarsim
from conftest import SOURCE_DIR, read_json, run_cli
from pcd_numpy import read_pcd

TINY = SOURCE_DIR / "tests" / "cli" / "campaign_tiny.json"  # 4 sequences of 2 frames


@pytest.fixture(scope="module")
def tiny_campaign(tmp_path_factory):
    out = tmp_path_factory.mktemp("campaign") / "tiny"
    run_cli("campaign", TINY, "--out", out, "--threads", 2, "--quiet")
    return out


def test_a_campaign_iterates_its_sequences_as_its_index_lists_them(tiny_campaign):
    index = read_json(tiny_campaign / "campaign.json")
    campaign = ladarsim.Campaign(tiny_campaign)
    assert campaign.index == index
    assert len(campaign) == len(index["sequences"]) == 4
    for sequence, entry in zip(campaign, index["sequences"]):
        assert (sequence.id, sequence.split, sequence.seed) == (entry["id"], entry["split"], entry["seed"])
        assert sequence.sampled == entry["sampled"]
        assert sequence.path == tiny_campaign / entry["directory"]
        assert sequence.scenario == read_json(tiny_campaign / entry["scenario"])
        frames = list(sequence.dataset)
        assert len(frames) == entry["frames"]
        # The returns by class, recounted from the frames by the classes drawn.
        class_of = {o["id"]: o["class"] for o in entry["sampled"]["objects"]}
        class_of.update({0: "background", 0xFFFFFFFF: "false_alarm"})
        counts = {}
        for k, frame in enumerate(frames):
            assert frame.points.tobytes() == read_pcd(sequence.path / "frames" / f"{k:06d}.pcd").tobytes()
            ids, n = np.unique(frame.points["object_id"], return_counts=True)
            for i, c in zip(ids.tolist(), n.tolist()):
                counts[class_of[i]] = counts.get(class_of[i], 0) + c
        assert counts == entry["returns_by_class"]
    assert campaign[-1].id == index["sequences"][-1]["id"]


def test_a_split_holds_its_sequences_alone(tiny_campaign):
    index = read_json(tiny_campaign / "campaign.json")
    seen = []
    for split in ("train", "val", "test"):
        ids = [s.id for s in ladarsim.Campaign(tiny_campaign, split=split)]
        assert ids == [e["id"] for e in index["sequences"] if e["split"] == split]
        seen += ids
    assert sorted(seen) == list(range(4))
    with pytest.raises(ValueError, match="split must be"):
        ladarsim.Campaign(tiny_campaign, split="training")


def test_a_directory_without_an_index_is_an_input_error(tmp_path):
    with pytest.raises(ladarsim.InputError) as error:
        ladarsim.Campaign(tmp_path)
    assert error.value.file == str(tmp_path / "campaign.json")
