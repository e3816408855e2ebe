//! 2-D geometry: contours of lines and arcs (polylines with bulge), pockets with islands,
//! and their import from DXF.
