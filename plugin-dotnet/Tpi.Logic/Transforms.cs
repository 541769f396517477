// 4x4 transforms as 16 numbers, row-major (RhinoCommon's Transform[row, column] read row by row;
// SurfaceSpec.Transformed's convention: a point p maps to M (p, 1)).
using System;

namespace Tpi.Logic
{
    /// <summary>What a transform does to a discrete surface.</summary>
    public enum TransformKind
    {
        /// <summary>Rotation, translation and uniform scale: tangent planes and their meeting points map exactly, neighbour choice unchanged, so the transformed mesh is the recomputed one.</summary>
        Similarity,
        /// <summary>Any other affine map (non-uniform scale, shear, mirror): meeting points map, but the neighbour choice (curvature metric) or the orientation may change: recompute.</summary>
        Affine,
        /// <summary>A projective map (bottom row not 0 0 0 1): the surface becomes rational: recompute.</summary>
        Projective,
    }

    /// <summary>Helpers for row-major 4x4 transforms.</summary>
    public static class Transforms
    {
        /// <summary>The identity.</summary>
        public static double[] Identity()
        {
            return new double[] { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
        }

        /// <summary>True if <paramref name="m"/> is exactly the identity.</summary>
        public static bool IsIdentity(double[] m)
        {
            Check(m, "m");
            for (int r = 0; r < 4; r++)
                for (int c = 0; c < 4; c++)
                    if (m[4 * r + c] != (r == c ? 1.0 : 0.0)) return false;
            return true;
        }

        /// <summary>a b: first b, then a.</summary>
        public static double[] Multiply(double[] a, double[] b)
        {
            Check(a, "a"); Check(b, "b");
            var m = new double[16];
            for (int r = 0; r < 4; r++)
                for (int c = 0; c < 4; c++)
                {
                    double sum = 0;
                    for (int k = 0; k < 4; k++) sum += a[4 * r + k] * b[4 * k + c];
                    m[4 * r + c] = sum;
                }
            return m;
        }

        /// <summary>
        /// Similarity if the linear part L satisfies L^T L = s^2 I with det L &gt; 0 (relative
        /// tolerance <paramref name="tolerance"/>), Projective if the bottom row is not (0 0 0 1),
        /// else Affine. A mirror is Affine: it turns the surface normals, so facet orientation
        /// and the envelope side change and the mesh must be recomputed.
        /// </summary>
        public static TransformKind Classify(double[] m, double tolerance = 1e-9)
        {
            Check(m, "m");
            if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1) return TransformKind.Projective;
            double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) + m[2] * (m[4] * m[9] - m[5] * m[8]);
            if (!(det > 0)) return TransformKind.Affine;
            double s2 = Math.Pow(det, 2.0 / 3.0);
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                {
                    double dot = 0;
                    for (int k = 0; k < 3; k++) dot += m[4 * k + i] * m[4 * k + j];
                    if (Math.Abs(dot - (i == j ? s2 : 0)) > tolerance * s2) return TransformKind.Affine;
                }
            return TransformKind.Similarity;
        }

        static void Check(double[] m, string name)
        {
            if (m == null) throw new ArgumentNullException(name);
            if (m.Length != 16) throw new ArgumentException("a transform has 16 numbers", name);
        }
    }
}
