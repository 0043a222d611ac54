"""Motion blur: how far and which way the camera moved, and the picture restored.

A camera on a moving arm smears every edge along one straight line. Such a blur
multiplies the image spectrum by a sinc whose zeros repeat every 1/L along the motion;
in the cepstrum (the inverse transform of the log spectrum) those zeros add up to a
sharp negative peak at the offset (L cos a, L sin a). The deepest point of the cepstrum
between `MIN_LENGTH` and `MAX_LENGTH` pixels from its centre gives length and direction,
refined to a fraction of a pixel by the centroid of its neighbours. A Wiener filter with
that straight-line kernel then undoes the blur (the renders are flat colours with dark
outlines, so the restored picture is close to the drawn one); a vertical shake is a
column of whole pixels, and its kernel is that column (`axis_kernel`). The restoration
is kept only when it gives edges back: an estimate that does not sharpen the picture (a blur
that is not a straight shake, or noise that hides the cepstrum's peak) leaves the image
as it was, and the blur warning stands.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from verigraph.perception.correct.noise import sharpness

MIN_LENGTH = 3  # px: shorter shakes do not reach the blur warning
MAX_LENGTH = 30  # px: longer ones leave too little of a thin object to restore
BALANCE = 0.005  # Wiener noise-to-signal balance for an 8-bit render (no sensor noise)
NOISY_BALANCE = 0.03  # ... once noise had to be filtered out
OBLIQUE_BALANCE = 0.015  # added at 45 degrees (as sin^2 of twice the angle): see oblique
PAD = 32  # px of mirrored border, so the periodic transform does not wrap edges
# The kernel that restores best is half a pixel longer than the cepstrum's peak: on
# kitchens shaken 9 px in random directions, 15 of 15 came back exact with it against 10
# at the peak's own length (and 9 of 10 on a second set of scenes); a longer kernel
# rings.
LENGTH_BIAS = 0.5
GAIN = 1.3  # restored sharpness over the blurred one below which the estimate is wrong
MIN_EDGES = 60.0  # sharpness below which there are no edges to estimate a shake from
AXIS_DEGREES = 1.0  # a shake this close to vertical is restored as a column of pixels


@dataclass(frozen=True, slots=True)
class MotionBlur:
    """A straight camera shake: `length` pixels at `degrees` (counter-clockwise from the
    image's x axis, 0-180)."""

    length: float
    degrees: float

    def describe(self) -> str:
        return f"{self.length:.1f} px at {self.degrees:.0f} degrees"


@dataclass(frozen=True, slots=True)
class Restoration:
    """A restored picture, the blur that was undone and the sharpness before and after."""

    image: np.ndarray
    blur: MotionBlur
    before: float
    after: float

    def note(self) -> str:
        return (f"a motion blur of {self.blur.describe()} was estimated and undone "
                f"(Wiener deconvolution; edge sharpness {self.before:.0f} -> "
                f"{self.after:.0f})")


def estimate_motion(image: np.ndarray) -> MotionBlur | None:
    """Length and direction of a straight motion blur, from the cepstrum's deepest point
    (None when the image is too small to hold one)."""
    grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY).astype(np.float32)
    h, w = grey.shape
    if min(h, w) <= 2 * MAX_LENGTH + 2:
        return None
    window = np.outer(np.hanning(h), np.hanning(w)).astype(np.float32)
    spectrum = np.fft.fft2((grey - float(grey.mean())) * window)
    cepstrum = np.fft.fftshift(np.real(np.fft.ifft2(np.log(np.abs(spectrum) + 1e-3))))
    cy, cx = h // 2, w // 2
    r = MAX_LENGTH
    ys, xs = np.mgrid[-r:r + 1, -r:r + 1]
    patch = cepstrum[cy - r:cy + r + 1, cx - r:cx + r + 1].copy()
    # A ring; the offset and its mirror are the same shake, so the lower half suffices
    # but the ring keeps the neighbourhood of every peak whole.
    radius = np.hypot(xs, ys)
    patch[(radius < MIN_LENGTH) | (radius > MAX_LENGTH - 1)] = np.inf
    iy, ix = np.unravel_index(int(np.argmin(patch)), patch.shape)
    near = patch[iy - 1:iy + 2, ix - 1:ix + 2]
    weight = np.where(np.isfinite(near), -near, 0.0)
    weight = np.maximum(weight - 0.3 * float(weight.max()), 0.0)
    if float(weight.sum()) <= 0:
        return None
    dx = float((weight * xs[iy - 1:iy + 2, ix - 1:ix + 2]).sum() / weight.sum())
    dy = float((weight * ys[iy - 1:iy + 2, ix - 1:ix + 2]).sum() / weight.sum())
    return MotionBlur(length=float(np.hypot(dx, dy)) + LENGTH_BIAS,
                      degrees=float(np.degrees(np.arctan2(-dy, dx)) % 180.0))


def axis_kernel(blur: MotionBlur) -> np.ndarray | None:
    """The column of whole pixels a vertical shake is, or None for any other direction.

    The anti-aliased line of `motion_kernel` spreads its ends over two pixels each: it
    is the right model between pixels, but along a column it is wider and softer than
    the camera's smear. Deconvolving a vertical shake with it leaves a ghost of a thin
    horizontal shape (a plate lying on a book or a desk) above and below it, which
    splits the plate in two or merges it into its support; with the exact column,
    tableware shaken 9 px vertically came back exact in 14 of 15 scenes against 12
    with the line, and in 18 of 20 against 14 on a second set. Along a row the line
    stays: the box restored the same graphs there but rang at the frame's left edge
    (an unexplained sliver that flagged 3 of 20 exact graphs). The column has the
    cepstrum's own length (`LENGTH_BIAS` taken back off), rounded to whole pixels."""
    if abs(blur.degrees % 180.0 - 90.0) > AXIS_DEGREES:
        return None
    n = max(1, int(round(blur.length - LENGTH_BIAS)))
    size = (n + 2) | 1
    kernel = np.zeros((size, size), np.float32)
    start = size // 2 - n // 2
    kernel[start:start + n, size // 2] = 1.0 / n
    return kernel


def motion_kernel(blur: MotionBlur) -> np.ndarray:
    """A straight line of `blur.length` pixels through the centre, anti-aliased
    (each sample shared bilinearly among its four pixels), summing to 1; for a vertical
    shake, the column of whole pixels (`axis_kernel`)."""
    box = axis_kernel(blur)
    if box is not None:
        return box
    size = (int(np.ceil(blur.length)) | 1) + 2
    kernel = np.zeros((size, size), np.float32)
    centre = (size - 1) / 2.0
    t = np.radians(blur.degrees)
    half = (blur.length - 1.0) / 2.0
    steps = np.linspace(-half, half, max(2, int(4 * blur.length)))
    x, y = centre + steps * np.cos(t), centre - steps * np.sin(t)
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    fx, fy = x - x0, y - y0
    for ox, oy, share in ((0, 0, (1 - fx) * (1 - fy)), (1, 0, fx * (1 - fy)),
                          (0, 1, (1 - fx) * fy), (1, 1, fx * fy)):
        np.add.at(kernel, (np.clip(y0 + oy, 0, size - 1), np.clip(x0 + ox, 0, size - 1)),
                  share.astype(np.float32))
    return kernel / np.float32(kernel.sum())


def oblique_balance(blur: MotionBlur) -> float:
    """Extra Wiener balance for a shake that is not along a pixel axis.

    The balance stands for what the kernel does not explain. Along a row or a column a
    shake is a box of whole pixels and the straight-line kernel is the blur itself; at
    an angle the camera's smear falls between pixels, and the line model misses that
    spread most at 45 degrees. Deconvolving with the too-sharp model there draws
    echoes of every edge one shake-length away; on a kitchen their bright echoes cut a
    silver pot's outline or a shelf's thin top. The extra balance grows as
    sin^2(2 angle): none along the axes, where the sharp restoration keeps the gap
    between stacked blocks, `OBLIQUE_BALANCE` at 45 degrees."""
    return OBLIQUE_BALANCE * float(np.sin(np.radians(2.0 * blur.degrees))) ** 2


def wiener(image: np.ndarray, kernel: np.ndarray, balance: float = BALANCE) -> np.ndarray:
    """The image deconvolved by `kernel` (per channel, in the frequency domain)."""
    src = cv2.copyMakeBorder(image, PAD, PAD, PAD, PAD, cv2.BORDER_REFLECT)
    src = src.astype(np.float32)
    h, w = src.shape[:2]
    psf = np.zeros((h, w), np.float32)
    kh, kw = kernel.shape
    psf[:kh, :kw] = kernel
    psf = np.roll(psf, (-(kh // 2), -(kw // 2)), axis=(0, 1))
    transfer = np.fft.rfft2(psf)
    inverse = np.conj(transfer) / (np.abs(transfer) ** 2 + balance)
    out = np.empty_like(src)
    for ch in range(src.shape[2]):
        out[..., ch] = np.fft.irfft2(np.fft.rfft2(src[..., ch]) * inverse, s=(h, w))
    return np.clip(out[PAD:-PAD, PAD:-PAD] + 0.5, 0, 255).astype(np.uint8)


def restore(image: np.ndarray, before: float, *, noisy: bool = False
            ) -> Restoration | None:
    """The picture with its motion blur undone, or None when no straight shake explains
    it (the restored picture is not sharper than `before` by `GAIN`, in the blur
    warning's own measure). A picture without edges (`MIN_EDGES`: an empty room) has
    no shake to find: deconvolving it only draws ringing."""
    if before < MIN_EDGES:
        return None
    blur = estimate_motion(image)
    if blur is None:
        return None
    balance = NOISY_BALANCE if noisy else BALANCE + oblique_balance(blur)
    restored = wiener(image, motion_kernel(blur), balance)
    after = sharpness(restored)
    if after < GAIN * before:
        return None
    return Restoration(image=restored, blur=blur, before=before, after=after)
