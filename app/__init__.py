"""Interactive explorer of Zharii's (1996) contact solution: a thin Panel layer over core."""
