//! Name lookup on small in-memory libraries: scoping order, imports, inheritance,
//! encapsulation and lazy loading.

use unimo_flat::lookup::Found;
use unimo_flat::{ClassTree, MemoryProvider};

fn library() -> MemoryProvider {
    let files = [
        ("Lib/package.mo", "within; package Lib constant Real k = 1; end Lib;"),
        (
            "Lib/Types.mo",
            "within Lib; package Types type Speed = Real(unit = \"m/s\"); type Big = Speed; end Types;",
        ),
        (
            "Lib/Parts/package.mo",
            "within Lib; package Parts partial model Base Lib.Types.Speed v; end Base; end Parts;",
        ),
        (
            "Lib/Parts/Car.mo",
            "within Lib.Parts; model Car extends Base; import T = Lib.Types; T.Big top; end Car;",
        ),
        ("Other/package.mo", "within; package Other model Unused end Unused; end Other;"),
    ];
    MemoryProvider::new().with_root(
        "lib",
        files.iter().map(|(p, t)| (p.to_string(), t.to_string())),
    )
}

fn class(tree: &mut ClassTree<'_>, path: &[&str]) -> unimo_flat::ClassId {
    match tree.lookup_dotted(None, path, false) {
        Some(Found::Class(c)) => c,
        other => panic!("{path:?}: {other:?}"),
    }
}

#[test]
fn finds_classes_through_packages_files_and_folders() {
    let provider = library();
    let mut tree = ClassTree::new(&provider);
    let car = class(&mut tree, &["Lib", "Parts", "Car"]);
    assert_eq!(tree.full_name(car), "Lib.Parts.Car");
    // `Base` is a sibling in the package folder's package.mo.
    let base = tree.lookup_simple(Some(car), "Base", false);
    assert!(matches!(base, Some(Found::Class(c)) if tree.full_name(c) == "Lib.Parts.Base"));
    // `T` is a renamed import of `Lib.Types`.
    assert!(matches!(
        tree.lookup_dotted(Some(car), &["T", "Big"], false),
        Some(Found::Class(_))
    ));
    // `v` is inherited from `Base`; `k` is a constant of the enclosing package.
    assert!(matches!(
        tree.lookup_simple(Some(car), "v", false),
        Some(Found::Component(_))
    ));
    assert!(matches!(
        tree.lookup_simple(Some(car), "k", false),
        Some(Found::Component(_))
    ));
    assert_eq!(tree.lookup_simple(Some(car), "nothing", false), None);
    // Short classes extend their base.
    let big = class(&mut tree, &["Lib", "Types", "Big"]);
    let bases = tree.bases(big);
    assert_eq!(bases.len(), 1);
    assert_eq!(tree.full_name(bases[0]), "Lib.Types.Speed");
}

#[test]
fn loads_only_what_is_looked_up() {
    let provider = library();
    let mut tree = ClassTree::new(&provider);
    class(&mut tree, &["Lib", "Types"]);
    // Lib/package.mo and Lib/Types.mo only: not Parts, not Other.
    assert_eq!(tree.stats.library_files, 2);
    class(&mut tree, &["Lib", "Types"]);
    assert_eq!(tree.stats.library_files, 2, "a second lookup reads nothing");
}

#[test]
fn encapsulated_classes_see_only_imports_and_builtins() {
    let provider = library();
    let mut tree = ClassTree::new(&provider);
    let text = "encapsulated model E import Lib.Types.Speed; Speed s; Real r; end E;";
    let file = tree.sources.add("e.mo", text);
    let parsed = unimo_syntax::parse(file, text);
    let ids = tree.add_user_file(file, parsed.ast);
    let e = ids[0];
    assert!(matches!(
        tree.lookup_simple(Some(e), "Speed", false),
        Some(Found::Class(_))
    ));
    assert!(matches!(
        tree.lookup_simple(Some(e), "Real", false),
        Some(Found::Builtin("Real"))
    ));
    assert_eq!(tree.lookup_simple(Some(e), "Lib", false), None);
}

#[test]
fn extends_names_do_not_see_their_own_inherited_members() {
    let provider = MemoryProvider::new();
    let mut tree = ClassTree::new(&provider);
    let text = "package P model A model Inner end Inner; end A; model B extends A; extends Inner; end B; end P;";
    let file = tree.sources.add("p.mo", text);
    let parsed = unimo_syntax::parse(file, text);
    let p = tree.add_user_file(file, parsed.ast)[0];
    let b = tree.child_class(p, "B").unwrap();
    // `Inner` is inherited from A, so B can use it as a member ...
    assert!(matches!(
        tree.lookup_simple(Some(b), "Inner", false),
        Some(Found::Class(_))
    ));
    // ... but not to name its own base class (spec 5.6.1).
    assert_eq!(tree.lookup_simple(Some(b), "Inner", true), None);
}

/// A library whose files exist but cannot be read (a permission error, say).
struct Unreadable;

impl unimo_flat::SourceProvider for Unreadable {
    fn roots(&self) -> usize {
        1
    }
    fn exists(&self, _: &unimo_flat::LibFile) -> bool {
        true
    }
    fn read(&self, _: &unimo_flat::LibFile) -> Result<String, String> {
        Err("permission denied".into())
    }
    fn list(&self, _: &unimo_flat::LibLocation) -> Vec<String> {
        Vec::new()
    }
    fn display(&self, file: &unimo_flat::LibFile) -> std::path::PathBuf {
        format!("lib/{}", file.path).into()
    }
}

/// A library file that cannot be read is `LibraryError::Unreadable`: `E0001` with the
/// file and the provider's reason, and the name is not found.
#[test]
fn an_unreadable_library_file_is_e0001() {
    let provider = Unreadable;
    let mut tree = ClassTree::new(&provider);
    assert!(tree.lookup_dotted(None, &["Lib"], false).is_none());
    let d = &tree.diagnostics[0];
    assert_eq!(d.code.0, "E0001");
    assert_eq!(
        d.message,
        "cannot read `lib/Lib/package.mo`: permission denied"
    );
    assert!(d.is_error());
}
