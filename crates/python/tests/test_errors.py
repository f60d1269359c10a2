"""Bad inputs raise Python exceptions with the library's one-line messages."""

import numpy as np
import pytest

import rslam

IMAGE = np.zeros((48, 64, 3), np.uint8)


def test_wrong_dtype_is_a_type_error_naming_the_dtype():
    with pytest.raises(TypeError, match="expected dtype uint8, got float32"):
        rslam.corrupt(IMAGE.astype(np.float32), 1, "fog")


def test_not_an_array_is_a_type_error():
    with pytest.raises(TypeError, match="expected a numpy array of uint8, got list"):
        rslam.corrupt([[1, 2, 3]], 1, "fog")


@pytest.mark.parametrize("shape", [(48, 64, 2), (48, 64, 5), (2, 48, 64, 3), (64,), (0, 64, 3)])
def test_wrong_shape_is_a_value_error_naming_the_shape(shape):
    with pytest.raises(ValueError, match=r"image: (expected shape HxWx3|empty image)"):
        rslam.corrupt(np.zeros(shape, np.uint8), 1, "fog")


def test_unknown_name_lists_the_valid_ones():
    with pytest.raises(ValueError) as error:
        rslam.corrupt(IMAGE, 1, "fgo")
    message = str(error.value)
    assert message.startswith("unknown corruption 'fgo'; valid: gaussian_noise, shot_noise")
    assert all(name in message for name in rslam.get_corruption_names("all"))


@pytest.mark.parametrize("severity", [0, 6, -1])
def test_severity_outside_1_to_5(severity):
    with pytest.raises(ValueError, match=f"severity must be an integer 1-5, got {severity}"):
        rslam.corrupt(IMAGE, severity, "fog")


def test_severity_not_an_integer():
    with pytest.raises(TypeError, match="severity must be an integer 1-5, got 2.5"):
        rslam.corrupt(IMAGE, 2.5, "fog")


def test_no_name_and_no_number():
    with pytest.raises(ValueError, match="either corruption_name or corruption_number"):
        rslam.corrupt(IMAGE, 1)


def test_number_out_of_range():
    with pytest.raises(ValueError, match="corruption_number 19: expected 0-18"):
        rslam.corrupt(IMAGE, 1, corruption_number=19)


def test_unknown_subset():
    with pytest.raises(ValueError, match="unknown subset 'bogus'; valid: common, validation"):
        rslam.get_corruption_names("bogus")


def test_perturber_unknown_item_lists_the_valid_names():
    with pytest.raises(ValueError) as error:
        rslam.Perturber("fgo:3")
    message = str(error.value)
    assert "unknown perturbation 'fgo'; valid:" in message
    assert "depth_missing" in message and "misalign" in message


@pytest.mark.parametrize("spec", ["fog:6", "fog:5.5", "fog:2.125", "fog:-1"])
def test_perturber_severity_outside_0_to_5(spec):
    with pytest.raises(ValueError, match=f"spec item '{spec}': .*0-5"):
        rslam.Perturber(spec)


def test_perturber_refuses_a_real_severity_where_the_item_takes_whole_ones():
    with pytest.raises(ValueError, match="saturate takes whole severities 0-5 only"):
        rslam.Perturber("saturate:2.5")


def test_perturber_refuses_sequence_items():
    with pytest.raises(ValueError, match="'misalign:5': misalign acts on a sequence of frames in time"):
        rslam.Perturber("fog:1,misalign:5")


def test_depth_corruption_without_depth():
    with pytest.raises(ValueError, match="depth corruptions need depth"):
        rslam.Perturber("depth_missing:3").apply(IMAGE)


def test_uint16_depth_needs_a_scale():
    depth = np.ones((48, 64), np.uint16)
    with pytest.raises(ValueError, match="uint16 depth needs depth_scale"):
        rslam.Perturber("depth_missing:3").apply(IMAGE, depth)


def test_depth_of_another_size():
    with pytest.raises(ValueError, match="does not match the colour's 64x48"):
        rslam.Perturber("depth_missing:3").apply(IMAGE, np.ones((40, 64), np.float32))


def test_depth_of_wrong_dtype():
    with pytest.raises(TypeError, match="expected dtype float32"):
        rslam.Perturber("depth_missing:3").apply(IMAGE, np.ones((48, 64), np.float64))


def test_frame_given_twice_in_a_batch():
    with pytest.raises(ValueError, match="frame index 3 is given twice"):
        rslam.Perturber("fog:1").apply_batch(np.zeros((2, 48, 64, 3), np.uint8), frame_indices=[3, 3])


def test_camera_size_is_enforced():
    p = rslam.Perturber("fog:1", camera="64,40,50,50,31.5,19.5")
    with pytest.raises(ValueError, match="64x48 frames given to a Perturber built for the 64x40"):
        p.apply(IMAGE)


def test_bad_camera():
    with pytest.raises(ValueError, match="camera"):
        rslam.Perturber("fog:1", camera="64,40")


def test_eval_without_matching_timestamps():
    est = np.array([[t, t, 0, 0, 0, 0, 0, 1] for t in range(5)], float)
    gt = est.copy()
    gt[:, 0] += 100.0
    with pytest.raises(ValueError, match="no matching timestamps"):
        rslam.eval.ate(est, gt)
