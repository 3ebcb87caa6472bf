"""propwhirl — wing flutter, propeller whirl flutter and divergence of flexible wings carrying
flexibly mounted propellers (the method of Liu Xu, *Propeller-Wing Whirl Flutter*, TU Delft 2020).

SI units throughout.  The equations of motion are derived symbolically (`derivations/`) and
generated into plain NumPy (`propwhirl.generated`); this package assembles and analyses them.
"""
__version__ = "0.1.0"
