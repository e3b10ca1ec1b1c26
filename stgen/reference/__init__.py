"""NumPy reference for the Stewart-platform kinematics (docs/mathematics.md sections 1–4).

The generated ST is proven against these functions. Modules, one job each:

* :mod:`~stgen.reference.geometry`   joints [2–4] and the rotation [6,7]
* :mod:`~stgen.reference.kinematics` IK [5–12], FK residual and Jacobian [36]
* :mod:`~stgen.reference.linalg`     Leibniz determinant, Doolittle LU
* :mod:`~stgen.reference.forward`    Newton–Raphson FK [13–18, 34–36]
* :mod:`~stgen.reference.cycloidal`  cycloidal point-to-point [19–28]
* :mod:`~stgen.reference.wave`       ocean wave [29–33]
"""

from stgen.reference.cycloidal import cycloidal_duration, cycloidal_fraction, cycloidal_pose, cycloidal_velocity
from stgen.reference.forward import ForwardKinematicsResult, NewtonRaphsonSolver, forward_kinematics
from stgen.reference.geometry import (
    base_joints,
    joint_angles,
    platform_joints,
    pose_to_degrees,
    pose_to_radians,
    rotation_matrix,
)
from stgen.reference.kinematics import InverseKinematicsResult, LegVectors, inverse_kinematics, jacobian, leg_vectors, residual
from stgen.reference.linalg import SingularMatrixError, leibniz_det, lu_doolittle, lu_solve, permutation_table, solve
from stgen.reference.wave import AIRY, RANDOM_5, OceanWave, WaveComponent, wave_pose

__all__ = [
    "AIRY",
    "RANDOM_5",
    "ForwardKinematicsResult",
    "InverseKinematicsResult",
    "LegVectors",
    "NewtonRaphsonSolver",
    "OceanWave",
    "SingularMatrixError",
    "WaveComponent",
    "base_joints",
    "cycloidal_duration",
    "cycloidal_fraction",
    "cycloidal_pose",
    "cycloidal_velocity",
    "forward_kinematics",
    "inverse_kinematics",
    "jacobian",
    "joint_angles",
    "leg_vectors",
    "leibniz_det",
    "lu_doolittle",
    "lu_solve",
    "permutation_table",
    "platform_joints",
    "pose_to_degrees",
    "pose_to_radians",
    "residual",
    "rotation_matrix",
    "solve",
    "wave_pose",
]
