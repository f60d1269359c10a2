# The reference libraries rslam's image corruptions are timed against, shared by
# scripts/bench-python.py (in memory) and scripts/bench_corruptions.py (file in -> file out):
# albumentations' closest transform per imagecorruptions name, with severity-3-like parameters
# (None: albumentations has no counterpart). Imported, not run.
import albumentations as A

ALBUMENTATIONS = {
    "gaussian_noise": lambda: A.GaussNoise(std_range=(0.18, 0.18), p=1),
    "shot_noise": lambda: A.ShotNoise(scale_range=(0.08, 0.08), p=1),
    "impulse_noise": lambda: A.SaltAndPepper(amount=(0.09, 0.09), p=1),
    "defocus_blur": lambda: A.Defocus(radius=(6, 6), alias_blur=(0.5, 0.5), p=1),
    "glass_blur": lambda: A.GlassBlur(sigma=1.0, max_delta=2, iterations=3, p=1),
    "motion_blur": lambda: A.MotionBlur(blur_limit=(31, 31), p=1),
    "zoom_blur": lambda: A.ZoomBlur(max_factor=(1.2, 1.2), step_factor=(0.02, 0.02), p=1),
    "snow": lambda: A.RandomSnow(p=1),
    "frost": None,
    "fog": lambda: A.RandomFog(p=1),
    "brightness": lambda: A.RandomBrightnessContrast(brightness_limit=(0.3, 0.3),
                                                     contrast_limit=(0, 0), p=1),
    "contrast": lambda: A.RandomBrightnessContrast(brightness_limit=(0, 0),
                                                   contrast_limit=(-0.8, -0.8), p=1),
    "elastic_transform": lambda: A.ElasticTransform(alpha=21.25, sigma=6.8, p=1),
    "pixelate": lambda: A.Downscale(scale_range=(0.4, 0.4), p=1),
    "jpeg_compression": lambda: A.ImageCompression(quality_range=(15, 15), p=1),
    "speckle_noise": lambda: A.MultiplicativeNoise(multiplier=(0.65, 1.35), elementwise=True, p=1),
    "gaussian_blur": lambda: A.GaussianBlur(sigma_limit=(3, 3), blur_limit=0, p=1),
    "spatter": lambda: A.Spatter(p=1),
    "saturate": lambda: A.HueSaturationValue(hue_shift_limit=0, sat_shift_limit=(60, 60),
                                             val_shift_limit=0, p=1),
}
