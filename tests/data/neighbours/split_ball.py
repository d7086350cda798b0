# Two labels of one voxelised ball (1 mm voxels, radius 9 mm), split by a
# plane tilted 35 degrees from the slices' normal and bent: neighbours
# whose pixel-lattice contours touch on every plane and overlap on none.
import numpy as np
n = 24
z, y, x = np.mgrid[0:n, 0:n, 0:n].astype(float)
c = (n - 1) / 2
inside = (x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2 <= 9.0 ** 2
cut = (x - c) - 0.7 * (z - c) - 0.05 * (y - c) ** 2
labels = np.where(inside, np.where(cut < 0, 1, 2), 0).astype(np.uint8)
with open('split-ball.nrrd', 'wb') as f:
    f.write(b"NRRD0004\ntype: uint8\ndimension: 3\nspace: left-posterior-superior\n"
            b"sizes: %d %d %d\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n"
            b"space origin: (0,0,0)\nencoding: raw\n\n" % (n, n, n))
    f.write(labels.tobytes(order='C'))
print((labels == 1).sum(), (labels == 2).sum())
