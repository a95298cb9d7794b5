"""ladarsim.Sensor: presets and sensor files, their documents as `ladarsim sensor show` prints
them and their derived quantities."""
import json

import pytest

import ladarsim
from conftest import SOURCE_DIR, run_cli


def test_a_preset_is_the_document_the_command_line_shows():
    sensor = ladarsim.Sensor.preset("paper_ladar")
    assert sensor.document == json.loads(run_cli("sensor", "show", "--preset", "paper_ladar"))
    derived = sensor.derived
    assert (sensor.columns, sensor.rows) == (derived["beams_az"], derived["beams_el"]) == (150, 20)
    assert sensor.pitch_az_mrad == derived["beam_pitch_az_mrad"]
    assert sensor.pitch_el_mrad == derived["beam_pitch_el_mrad"]
    assert sensor.beams_per_second == derived["beams_per_second"]
    assert sensor.pulses_per_beam == derived["pulses_per_beam"]
    # The paper's figures: 150 x 20 beams at 20 frames/s over a 0.5 deg field.
    assert sensor.beams_per_second == pytest.approx(60000)
    assert sensor.field_az_deg == pytest.approx(0.5)


def test_a_sensor_file_reads_as_its_preset_and_a_typo_names_file_and_key(tmp_path):
    assert set(ladarsim.Sensor.presets()) >= {"paper_ladar", "velodyne_vlp16"}
    bundled = SOURCE_DIR / "assets" / "sensors" / "velodyne_vlp16.json"
    assert ladarsim.Sensor.from_file(bundled).document == ladarsim.Sensor.preset("velodyne_vlp16").document
    document = json.loads(bundled.read_text())
    document["scan"]["colums"] = 1
    broken = tmp_path / "broken.json"
    broken.write_text(json.dumps(document))
    with pytest.raises(ladarsim.InputError) as error:
        ladarsim.Sensor.from_file(broken)
    assert error.value.file == str(broken) and error.value.field == "scan.colums"
    document["scan"].pop("colums")
    document["scan"]["chanels"] = document["scan"].pop("channels")
    with pytest.raises(ladarsim.InputError) as error:
        ladarsim.Sensor.from_document(document)
    # A misspelt required key, in a dict named as Python names what is not a file.
    assert error.value.file == "<sensor dict>" and error.value.field == "scan.chanels"
    assert error.value.problem == 'unknown key; did you mean "channels"?'
    with pytest.raises(ValueError, match="the presets are .*paper_ladar"):
        ladarsim.Sensor.preset("paper_lader")
