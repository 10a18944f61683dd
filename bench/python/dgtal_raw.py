"""A DGtal .vol's voxels as a headerless raw file, for the benches that need one file every tool reads."""
import os
import re
import zlib


def dgtal_to_raw(vol, out_dir):
    """Writes `vol`'s voxels (uint8, X fastest) to out_dir/<stem>_<X>x<Y>x<Z>_uint8.raw; returns (path, dims)."""
    data = open(vol, "rb").read()
    end = data.index(b"\n.\n") + 3
    header = data[:end].decode("ascii", "replace")
    dims = [int(re.search(r"^%s:\s*(\d+)" % a, header, re.M).group(1)) for a in "XYZ"]
    raw = os.path.join(out_dir, "%s_%dx%dx%d_uint8.raw" % (os.path.basename(vol).split(".")[0], *dims))
    payload = data[end:]
    if re.search(r"^Version:\s*3", header, re.M):  # version 3: the voxels are zlib-compressed
        payload = zlib.decompress(payload)
    with open(raw, "wb") as f:
        f.write(payload[:dims[0] * dims[1] * dims[2]])
    return raw, dims
