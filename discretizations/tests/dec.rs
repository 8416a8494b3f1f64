use tvf_core::generate::*;
use tvf_core::SurfaceMesh;
use tvf_core::geometry::{cross, dot, norm, sub};

fn cot(o: [f64;3], a: [f64;3], b: [f64;3]) -> f64 {
    let u = sub(a, o); let v = sub(b, o);
    dot(u, v) / norm(cross(u, v))
}
fn bad(mesh: &SurfaceMesh) -> (usize, f64) {
    let mut s = vec![0.0; mesh.edge_count()];
    for (t, e) in mesh.face_edges().iter().enumerate() {
        for c in 0..3 { s[e[c]] += cot(mesh.corner(t,c), mesh.corner(t,(c+1)%3), mesh.corner(t,(c+2)%3)); }
    }
    (s.iter().filter(|&&x| x <= 0.0).count(), s.iter().cloned().fold(f64::INFINITY, f64::min))
}
#[test]
fn survey() {
    let mut list: Vec<(String, SurfaceMesh)> = vec![];
    for l in 0..5 { list.push((format!("icosphere({l})"), icosphere(l))); }
    for g in 0..5 { for r in [2,4,8] { list.push((format!("genus_surface({g},{r})"), genus_surface(g, r))); } }
    list.push(("torus 16x8".into(), torus(1.0,0.4,16,8).unwrap()));
    list.push(("torus 24x6".into(), torus(2.0,0.3,24,6).unwrap()));
    list.push(("bumpy".into(), bumpy_torus(1.0,0.3,32,16,6,0.5).unwrap()));
    for amp in [0.02, 0.05, 0.1, 0.15] { for seed in 0..20 {
        let m = jitter(&icosphere(2), amp, seed).unwrap(); let (n, _) = bad(&m);
        if n > 0 { eprintln!("jitter ico2 amp {amp} seed {seed}: {n} bad"); }
        let m = jitter(&icosphere(1), amp, seed).unwrap(); let (n, _) = bad(&m);
        if n > 0 { eprintln!("jitter ico1 amp {amp} seed {seed}: {n} bad"); }
        let m = jitter(&icosphere(3), amp, seed).unwrap(); let (n, _) = bad(&m);
        if n > 0 { eprintln!("jitter ico3 amp {amp} seed {seed}: {n} bad"); }
        let m = jitter(&genus_surface(2,2), amp, seed).unwrap(); let (n, _) = bad(&m);
        if n > 0 { eprintln!("jitter g2 amp {amp} seed {seed}: {n} bad"); }
    }}
    for f in ["eight.obj","kitten.obj","3holes.obj","hand.obj","rocker-arm.obj","bumpy-torus.obj"] {
        let m = tvf_core::io::load_mesh(format!("../../shared/meshes/{f}")).unwrap().mesh;
        list.push((f.into(), m));
    }
    for (name, m) in &list {
        let (n, min) = bad(m);
        eprintln!("{name}: F={} E={} bad={n} min(cotα+cotβ)={min:.3e}", m.face_count(), m.edge_count());
    }
}

fn flip(mesh: &SurfaceMesh) -> SurfaceMesh {
    let positions = mesh.positions().to_vec();
    let mut faces = mesh.faces().to_vec();
    for _round in 0..100 {
        let m = SurfaceMesh::new(positions.clone(), faces.clone()).unwrap();
        let mut worst = None;
        let mut wv = 0.0;
        for (e, tf) in m.edge_faces().iter().enumerate() {
            let mut s = 0.0;
            for &t in tf { let c = m.face_edges()[t].iter().position(|&x| x==e).unwrap(); s += cot(m.corner(t,c), m.corner(t,(c+1)%3), m.corner(t,(c+2)%3)); }
            if s < wv { wv = s; worst = Some(e); }
        }
        let Some(e) = worst else { return m };
        let [s, t] = m.edge_faces()[e];
        let cs = m.face_edges()[s].iter().position(|&x| x==e).unwrap();
        let ct = m.face_edges()[t].iter().position(|&x| x==e).unwrap();
        let fs = faces[s]; let ft = faces[t];
        let (a, b, p) = (fs[(cs+1)%3], fs[(cs+2)%3], fs[cs]);
        let q = ft[ct];
        // faces (p, a, b) and (q, b, a) -> (p, a, q), (q, b, p)
        faces[s] = [p, a, q]; faces[t] = [q, b, p];
        if SurfaceMesh::new(positions.clone(), faces.clone()).is_err() { eprintln!("flip broke mesh"); return m; }
    }
    eprintln!("no convergence");
    SurfaceMesh::new(positions, faces).unwrap()
}

#[test]
fn flips() {
    for g in 1..4 { for r in [2, 4] { for amp in [0.0, 0.02, 0.05] {
        let m = jitter(&genus_surface(g, r), amp, 3).unwrap();
        let f = flip(&m);
        let (n, min) = bad(&f);
        eprintln!("g{g} r{r} amp{amp}: F={} genus {} bad {n} min {min:.3e} angles {:?}", f.face_count(), f.genus(), f.angle_range_deg());
    }}}
}
