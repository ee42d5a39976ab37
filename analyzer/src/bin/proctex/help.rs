//! The CLI's help texts: `proctex help` and each command's `--help`.

pub const MAIN_HELP: &str = "\
proctex — turn a photo of a material into a procedural texture (Lagae et al. 2009)

USAGE:
    proctex <COMMAND> [ARGS] [OPTIONS]

COMMANDS:
    analyze   PHOTO → params JSON
    render    params JSON → PNG (CPU reference renderer)
    synth     PHOTO → analysed texture rendered at exactly the photo's pixel size
    pyramid   PHOTO → raster texture by Heeger & Bergen's pyramid synthesis (any size, tiles)
    evaluate  texture distances between two images
    fidelity  synthesis-vs-photo distance ratios (README, Results)
    morph     params JSON files → the texture a fraction t of the way through them
    export    params JSON → params JSON, or a complete WGSL or GLSL shader of the texture or a morph
    build-db  the retrieval database of the structured models (analyzer/data/patterns.ptxdb)
    help      this text; `proctex <COMMAND> --help` for a command

OPTIONS FOR EVERY COMMAND:
    --max-pixels N   the most pixels a photo or a render may have (default: 50 MP for a photo,
                     8192×8192 for a render, 4096×4096 for a pyramid synthesis; a side is at
                     most 16384 either way)

Files over 256 MiB are refused unread.

Exit codes: 0 success, 1 bad input or failed operation, 2 bad usage.";

pub const ANALYZE_HELP: &str = "\
proctex analyze PHOTO [-o PARAMS.json] [--json] [OPTIONS]

Analyses PHOTO (PNG, JPEG, WebP, GIF, BMP, TIFF; 8/16-bit; EXIF orientation applied) and
writes the texture parameters (format proctex/1).

OPTIONS:
    -o, --output FILE       write the params JSON to FILE
    --json                  print the params JSON to stdout (the summary goes to stderr)
    --size N                analysis size: 256, 512 (default), 1024 or 2048; larger photos
                            are area-averaged until their longer side is N
    --crop X,Y,W,H          analyse only this rectangle (photo pixels)
    --no-histogram          no histogram matching (Lagae §5); knots are still stored
    --knots K               inverse-CDF intervals (default 10, at most 32)
    --seed S                seed of the noise (default 1)
    --estimator E           rings (default: the radial spectrum fitted on quarter-octave
                            rings), deconvolved (octave powers through the measured
                            leakage) or lagae (the paper's eq. 9)
    --no-periodic           skip the periodic+smooth decomposition before the FFT
    --isotropic             every noise band isotropic (no fitted orientation), as Lagae
    --no-tone               no output tone curve on the noise model (its channels
                            independent, as Lagae)
    --flatten-lighting      divide out the photo's lighting gradient first (the plane
                            through its log luminance): for a photo lit from one side; on
                            evenly lit photos it usually costs more than it gains
    --model M               auto (default): the nearest of every candidate below, by texture
                            distance; noise: Lagae's noise model; or a structured family:
                            perlin, turbulence, ridged, grid, brick, cells, planks,
                            wood_lines, rings (retrieved, refined, then fitted)
    --refine N              Nelder–Mead evaluations per refined family after retrieval
                            (the family classifier's first three, and the one --model
                            names), shared by its two best database entries as starts
                            (default 40; 0: retrieval alone)
    --refine-seconds S      a time budget for the refinement as well: it stops after S
                            seconds (each family keeps its best point so far) and says so;
                            the result then depends on the machine's speed (none by default)";

pub const RENDER_HELP: &str = "\
proctex render PARAMS.json -o OUT.png [OPTIONS]

Renders the texture with the CPU reference renderer.

OPTIONS:
    -o, --output FILE       the PNG to write (required)
    --size N                N×N pixels
    --width W --height H    W×H pixels (default: the analysed photo's size, else 512×512)
    --pixel-size P          world units per pixel (default 1 = one photo pixel)
    --origin X,Y            world coordinates of the top-left corner (default 0,0)
    --solid-z Z             render the solid (3D) texture's slice at world z = Z
    --period                render exactly one period of the texture (16384 texels for 8
                            bands, minified into the image)
    --seamless              a seamless N×N tile at the pixel size (--size N, 16..=8192):
                            every band made periodic over the tile, a structured model's
                            pattern turned to the nearest quarter turn with a whole number of
                            cells (what the app's PNG tile export renders); prints how its
                            wrap compares with its interior
    --depth 8|16            bits per channel of the PNG (default 8)";

pub const SYNTH_HELP: &str = "\
proctex synth PHOTO -o OUT.png [--model M] [--seed S] [analyze OPTIONS]

Analyses PHOTO with the model chosen as `analyze` does (--model auto by default; prints the
ranking and the model) and renders the texture at exactly PHOTO's pixel size (or the crop's),
at the photo's scale. Accepts the options of `analyze`.";

pub const PYRAMID_HELP: &str = "\
proctex pyramid PHOTO -o OUT.png [--width W --height H] [--iterations N] [--scales S]
                [--orientations K] [--seed S] [--crop X,Y,W,H] [--mix B.png --m M]
proctex pyramid PHOTO --solid N -o OUT_DIR [--iterations N] [--scales S] [--orientations K]
                [--seed S] [--crop X,Y,W,H]

Synthesises a raster texture like PHOTO (or the crop) with Heeger & Bergen's pyramid-based
synthesis (1995): noise whose every steerable-pyramid subband, both residuals included, is
matched to PHOTO's histogram in turn, N times; colours decorrelated by PCA, then each RGB
channel matched to PHOTO's. The output tiles seamlessly and may have any size.

    --width W, --height H   output size (default: PHOTO's or the crop's)
    --iterations N          rounds of the loop (default 5, at most 100)
    --scales S              pyramid scales (default 4; fewer where PHOTO or the output is small)
    --orientations K        orientations per scale (default 4, at most 16)
    --seed S                seed of the starting noise (default 1)
    --mix B.png --m M       a texture mixture (Heeger & Bergen §5): every subband's histogram,
                            the colours and the colour axes M of the way from PHOTO's to B's
                            (0: PHOTO's synthesis, 1: B's, when both allow the same scales)
    --solid N               a solid texture (Heeger & Bergen §4): an N³ volume (16 to 128,
                            64 usual) any slice of which looks like PHOTO, written as N PNG
                            slices along z (OUT_DIR/slice_000.png …); it tiles in 3D";

pub const EVALUATE_HELP: &str = "\
proctex evaluate A.png B.png [--json]

Prints texture distances between A and B (any sizes):
    spectrum_db  RMS difference in dB of radially averaged luminance power spectra
    colour       sliced Wasserstein-1 distance of the RGB distributions
    structure    weighted distance of the luminance's Gabor descriptors (orientation, scale and
                 distribution of structure; the retrieval descriptor)";

pub const MORPH_HELP: &str = "\
proctex morph A.json B.json [C.json...] --t T [-o OUT.json]

Interpolates the textures (Lagae §8): everything linearly except the colour basis (quaternion
slerp) and the scale (geometric); t in [0, 1] is spread evenly over the segments A→B→C…; the
noise uses A's seed. Prints the params JSON (or writes OUT.json).";

pub const BUILD_DB_HELP: &str = "\
proctex build-db -o FILE

Renders every structured model over its parameter space (320 samples per family, from the
project's hash: deterministic) and writes their Gabor descriptors, quantised to a byte each:
the database retrieval searches. The shipped one is analyzer/data/patterns.ptxdb, compiled into
the library; rebuild it when a pattern or the descriptor changes (a test says when).";

pub const EXPORT_HELP: &str = "\
proctex export PARAMS.json [MORE.json...] --format json|wgsl|glsl [-o OUT]

json: the validated params document. wgsl: a complete WGSL shader: the function
proctex(p, pixel_size) with the params baked in (and proctex3(p, pixel_size) for solid
textures), the passes that bake the noise tile from the seed (three; four into a slice atlas
for solid textures), and a full-screen vs_main/fs_main; its header comment says how to host it.
glsl: the same as GLSL ES 3.00 (WebGL2; desktop GLSL 330 by changing the #version line): the
display fragment shader as-is, and the vertex shader and bake passes by one #define each.

Two or more params files (wgsl, glsl): the morph through them, as `proctex morph`, with t as a
uniform: proctex(p, pixel_size, t) rebuilds the params of t from every file's constants.";
