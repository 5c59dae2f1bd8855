# SSIM of two luminance images (raw little-endian float64, rows of WIDTH) by scikit-image, the
# independent implementation tests/eval/ssim_reference_test.cpp compares ours with.
#   usage: python3 skimage_ssim.py A.f64 B.f64 WIDTH HEIGHT
import sys

import numpy as np
from skimage.metrics import structural_similarity

a_file, b_file, width, height = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
a = np.fromfile(a_file, dtype="<f8").reshape(height, width)
b = np.fromfile(b_file, dtype="<f8").reshape(height, width)
gaussian = structural_similarity(a, b, data_range=255, gaussian_weights=True, sigma=1.5,
                                 use_sample_covariance=False)
uniform7 = structural_similarity(a, b, data_range=255, win_size=7, use_sample_covariance=False)
print(f"{gaussian:.12f} {uniform7:.12f}")
