# Holds a connection to the X display until killed. Xvfb resets itself when its
# last client leaves, and a client connecting during the reset is refused: the
# window test starts the app more than once, so it keeps this one connected.
import ctypes, signal, sys
x = ctypes.cdll.LoadLibrary("libX11.so.6")
x.XOpenDisplay.restype = ctypes.c_void_p
x.XOpenDisplay.argtypes = [ctypes.c_char_p]
if not x.XOpenDisplay(None):
    sys.exit("cannot open display")
signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
while True:
    signal.pause()
